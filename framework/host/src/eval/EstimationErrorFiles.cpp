/// \file EstimationErrorFiles.cpp
/// pose_errors.csv and landmark_errors.csv; see EstimationErrorFiles.h.

#include <esif/core/Errors.h>
#include <esif/core/InputBounds.h>
#include <esif/core/NumberToken.h>
#include <esif/core/TextInput.h>
#include <esif/eval/EstimationErrorFiles.h>
#include <esif/safeio/AtomicFile.h>

#include <esif/formats/NumberText.h>

#include <cmath>
#include <filesystem>
#include <functional>

namespace esif
{
namespace
{
const char* const kPoseHeader = "step,ex_m,ey_m,eth_rad,nees,nees_position,nees_heading";
const char* const kPoseHeaderWithoutSplit = "step,ex_m,ey_m,eth_rad,nees";
const char* const kLandmarkHeader = "true_id,ex_m,ey_m,nees";

void appendNumber(std::string& out, double v)
{
	out += ',';
	number_text::append(out, v);
}

void appendNees(std::string& out, const std::optional<double>& v)
{
	out += ',';
	if (v) number_text::append(out, *v);
}

/// The comma-separated fields of `line`.
std::vector<std::string> fieldsOf(const std::string& line)
{
	std::vector<std::string> fields(1);
	for (const char c : line)
		if (c == ',')
			fields.emplace_back();
		else if (c != '\r')
			fields.back() += c;
	return fields;
}

double parseNumber(const std::string& field, const std::string& where)
{
	const auto v = doubleToken(field, NonFinite::accepted);
	if (!v) throw InputError(where + ": '" + field + "' is not a number");
	return *v;
}

/// An error of a position [m] or heading [rad]: finite and within the bound
/// of every coordinate esif reads (InputBounds.h); a NaN would be averaged
/// into a campaign's summary as "nan".
double parseError(const std::string& field, const std::string& where)
{
	const double v = parseNumber(field, where);
	if (!std::isfinite(v) || std::abs(v) > kMaxCoordinate_m)
		throw InputError(where + ": error '" + field + "' is not finite or beyond " + number_text::text(kMaxCoordinate_m));
	return v;
}

long long parseInteger(const std::string& field, const std::string& where)
{
	const auto v = integerToken<long long>(field);
	if (!v || *v < 0) throw InputError(where + ": '" + field + "' is not a non-negative integer");
	return *v;
}

std::optional<double> parseNees(const std::string& field, const std::string& where)
{
	if (field.empty()) return std::nullopt;
	const double v = parseNumber(field, where);
	if (!std::isfinite(v) || v < 0) throw InputError(where + ": NEES '" + field + "' is not a finite number >= 0");
	return v;
}

/// Calls `row(fields, where)` for every line after the header, which must
/// be `header` or, when given, `older_header` (a prefix of it: an earlier
/// version of the file); each line must have as many fields as the header
/// the file has.
void readCsv(
	const std::string& path, const std::string& header,
	const std::function<void(const std::vector<std::string>&, const std::string&)>& row,
	const char* older_header = nullptr)
{
	if (!pathPresent(path)) throw InputError(path + ": missing (was the run given ground truth?)");
	TextLineReader in(path, "estimation errors");
	std::string line;
	if (!in.next(line) ||
		(fieldsOf(line) != fieldsOf(header) && (!older_header || fieldsOf(line) != fieldsOf(older_header))))
		throw InputError(path + ":1: expected the header '" + header + "'");
	const std::size_t columns = fieldsOf(line).size();
	while (in.next(line))
	{
		if (line.empty()) continue;
		const std::string where = in.where();
		const auto fields = fieldsOf(line);
		if (fields.size() != columns)
			throw InputError(
				where + ": " + std::to_string(fields.size()) + " fields, expected " + std::to_string(columns));
		row(fields, where);
	}
}
}  // namespace

std::string poseErrorsCsv(const std::vector<PoseError>& rows)
{
	std::string out = std::string(kPoseHeader) + "\n";
	for (const auto& r : rows)
	{
		out += std::to_string(r.step);
		for (int i = 0; i < 3; ++i) appendNumber(out, r.error(i));
		appendNees(out, r.nees);
		appendNees(out, r.position_nees);
		appendNees(out, r.heading_nees);
		out += '\n';
	}
	return out;
}

std::string landmarkErrorsCsv(const std::vector<LandmarkError>& rows)
{
	std::string out = std::string(kLandmarkHeader) + "\n";
	for (const auto& r : rows)
	{
		out += std::to_string(r.true_id);
		for (int i = 0; i < 2; ++i) appendNumber(out, r.error(i));
		appendNees(out, r.nees);
		out += '\n';
	}
	return out;
}

void writeEstimationErrorFiles(
	const std::string& dir, const std::vector<PoseError>& poses, const std::vector<LandmarkError>& landmarks)
{
	writeTextAtomically((std::filesystem::path(dir) / kPoseErrorsFile).string(), poseErrorsCsv(poses));
	writeTextAtomically((std::filesystem::path(dir) / kLandmarkErrorsFile).string(), landmarkErrorsCsv(landmarks));
}

std::vector<PoseError> readPoseErrors(const std::string& path)
{
	std::vector<PoseError> rows;
	const auto parse = [&](const std::vector<std::string>& f, const std::string& where) {
		PoseError r;
		r.step = static_cast<std::size_t>(parseInteger(f[0], where));
		for (int i = 0; i < 3; ++i) r.error(i) = parseError(f[1 + i], where);
		r.nees = parseNees(f[4], where);
		if (f.size() > 5)
		{
			r.position_nees = parseNees(f[5], where);
			r.heading_nees = parseNees(f[6], where);
		}
		rows.push_back(r);
	};
	readCsv(path, kPoseHeader, parse, kPoseHeaderWithoutSplit);
	return rows;
}

std::vector<LandmarkError> readLandmarkErrors(const std::string& path)
{
	std::vector<LandmarkError> rows;
	readCsv(path, kLandmarkHeader, [&](const std::vector<std::string>& f, const std::string& where) {
		LandmarkError r;
		r.true_id = static_cast<LandmarkId>(parseInteger(f[0], where));
		for (int i = 0; i < 2; ++i) r.error(i) = parseError(f[1 + i], where);
		r.nees = parseNees(f[3], where);
		rows.push_back(r);
	});
	return rows;
}

}  // namespace esif
