#include <esif/io/ProgressBar.h>

#include <cstdio>
#include <unistd.h>

namespace esif
{
ProgressBar::ProgressBar(std::string label, std::size_t total)
	: label_(std::move(label)), total_(total), enabled_(::isatty(STDERR_FILENO) == 1 && total > 0)
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
	std::fprintf(stderr, "\r%s [%.*s%*s] %3d%% %zu/%zu", label_.c_str(), filled,
				 "########################################", kWidth - filled, "", static_cast<int>(100 * frac), done,
				 total_);
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
