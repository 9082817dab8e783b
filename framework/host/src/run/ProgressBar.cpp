#include <esif/run/ProgressBar.h>

#include <cstdio>
#include <string>
#include <unistd.h>

namespace esif
{
namespace
{
/// "ETA 1h02m", "ETA 3m05s", "ETA 12s"; "ETA ?" before the first item.
std::string etaText(std::size_t done, std::size_t total, double elapsed_s)
{
	if (done == 0) return " ETA ?";
	const long long left = static_cast<long long>(elapsed_s / static_cast<double>(done) * (total - done) + 0.5);
	char buf[48];
	if (left >= 3600)
		std::snprintf(buf, sizeof(buf), " ETA %lldh%02lldm", left / 3600, left % 3600 / 60);
	else if (left >= 60)
		std::snprintf(buf, sizeof(buf), " ETA %lldm%02llds", left / 60, left % 60);
	else
		std::snprintf(buf, sizeof(buf), " ETA %llds", left);
	return buf;
}
}  // namespace

ProgressBar::ProgressBar(std::string label, std::size_t total, bool show_eta)
	: label_(std::move(label)), total_(total), enabled_(::isatty(STDERR_FILENO) == 1 && total > 0), show_eta_(show_eta)
{
}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(std::size_t done)
{
	if (!enabled_ || finished_) return;
	const auto now = std::chrono::steady_clock::now();
	if (done < total_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
	last_draw_ = now;
	constexpr int kWidth = 40;
	const double frac = static_cast<double>(done) / static_cast<double>(total_);
	const int filled = static_cast<int>(frac * kWidth);
	const std::string eta =
		show_eta_ ? etaText(done, total_, std::chrono::duration<double>(now - start_).count()) : std::string();
	std::fprintf(stderr, "\r%s [%.*s%*s] %3d%% %zu/%zu%s\033[K", label_.c_str(), filled,
				 "########################################", kWidth - filled, "", static_cast<int>(100 * frac), done,
				 total_, eta.c_str());
	std::fflush(stderr);
}

void ProgressBar::finish()
{
	if (!enabled_ || finished_) return;
	finished_ = true;
	std::fprintf(stderr, "\r\033[K");
	std::fflush(stderr);
}

}  // namespace esif
