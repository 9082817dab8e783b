#pragma once
/// \file ParamBinder.h
/// One declaration per parameter, used both to load and validate it from an
/// INI section and to describe it (`esif plugins`, effective-parameter dumps),
/// so loading and documenting can never drift apart.
///
/// A parameter struct implements `void declare(ParamBinder& b)` calling
/// b.real(...), b.integer(...), b.flag(...), b.choice(...) once per field.

#include <cmath>
#include <deque>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace esif
{
class ConfigSection;

/// Allowed interval of a numeric parameter.
struct Bounds
{
	double lo = -std::numeric_limits<double>::infinity();
	double hi = std::numeric_limits<double>::infinity();
	bool lo_open = false;
	bool hi_open = false;

	static Bounds any() { return {}; }
	static Bounds positive() { return {0, Bounds{}.hi, true, false}; }
	static Bounds nonNegative() { return {0, Bounds{}.hi, false, false}; }
	static Bounds openUnit() { return {0, 1, true, true}; }
	static Bounds closed(double lo, double hi) { return {lo, hi, false, false}; }
	static Bounds atLeast(double lo) { return {lo, Bounds{}.hi, false, false}; }

	bool contains(double v) const;
	std::string text() const;  ///< e.g. "must be in (0, 1)"
};

/// Description of one parameter, for listings.
struct ParamInfo
{
	std::string key;
	std::string value;	///< default (or effective) value as INI text
	std::string doc;
};

class ParamBinder
{
   public:
	virtual ~ParamBinder() = default;
	virtual void real(const char* key, double& field, const char* doc, Bounds bounds) = 0;
	virtual void integer(const char* key, int& field, const char* doc, Bounds bounds) = 0;
	virtual void flag(const char* key, bool& field, const char* doc) = 0;
	virtual void text(const char* key, std::string& field, const char* doc) = 0;
	/// A string restricted to `options`; an unknown value is an error, never a default.
	virtual void choice(
		const char* key, std::string& field, const std::vector<std::string>& options,
		const char* doc) = 0;

	/// Enum parameter set by name: `table` maps INI names to values.
	template <class E>
	void enumeration(
		const char* key, E& field, const std::vector<std::pair<std::string, E>>& table,
		const char* doc)
	{
		std::vector<std::string> names;
		std::string current;
		for (const auto& [name, value] : table)
		{
			names.push_back(name);
			if (value == field) current = name;
		}
		choice(key, current, names, doc);
		for (const auto& [name, value] : table)
			if (name == current) field = value;
	}
};

/// Forwards every declaration to `target` with `prefix` put before the key,
/// so one parameter struct can be declared twice in one section (e.g. the
/// EKF association keys of a joining plugin's local-map builder as
/// `local_association`, `local_gate_chi2_quantile`, ...).
class PrefixedBinder : public ParamBinder
{
   public:
	PrefixedBinder(ParamBinder& target, std::string prefix) : target_(target), prefix_(std::move(prefix)) {}
	void real(const char* key, double& field, const char* doc, Bounds bounds) override
	{
		target_.real(name(key), field, doc, bounds);
	}
	void integer(const char* key, int& field, const char* doc, Bounds bounds) override
	{
		target_.integer(name(key), field, doc, bounds);
	}
	void flag(const char* key, bool& field, const char* doc) override { target_.flag(name(key), field, doc); }
	void text(const char* key, std::string& field, const char* doc) override { target_.text(name(key), field, doc); }
	void choice(
		const char* key, std::string& field, const std::vector<std::string>& options, const char* doc) override
	{
		target_.choice(name(key), field, options, doc);
	}

   private:
	const char* name(const char* key)
	{
		names_.push_back(prefix_ + key);
		return names_.back().c_str();
	}
	ParamBinder& target_;
	std::string prefix_;
	std::deque<std::string> names_;  // stable storage for the prefixed keys
};

/// Loads every declared parameter from `section` (absent keys keep their
/// defaults) and validates it; throws ConfigError naming section, key and rule.
template <class Params>
void loadParams(Params& params, const ConfigSection& section);

/// Lists every declared parameter with its current value.
template <class Params>
std::vector<ParamInfo> describeParams(Params params);

// ---- implementation -------------------------------------------------------
class LoadingBinder : public ParamBinder
{
   public:
	explicit LoadingBinder(const ConfigSection& section) : section_(section) {}
	void real(const char* key, double& field, const char* doc, Bounds bounds) override;
	void integer(const char* key, int& field, const char* doc, Bounds bounds) override;
	void flag(const char* key, bool& field, const char* doc) override;
	void text(const char* key, std::string& field, const char* doc) override;
	void choice(
		const char* key, std::string& field, const std::vector<std::string>& options,
		const char* doc) override;

   private:
	const ConfigSection& section_;
};

class DescribingBinder : public ParamBinder
{
   public:
	void real(const char* key, double& field, const char* doc, Bounds bounds) override;
	void integer(const char* key, int& field, const char* doc, Bounds bounds) override;
	void flag(const char* key, bool& field, const char* doc) override;
	void text(const char* key, std::string& field, const char* doc) override;
	void choice(
		const char* key, std::string& field, const std::vector<std::string>& options,
		const char* doc) override;
	std::vector<ParamInfo> infos;
};

template <class Params>
void loadParams(Params& params, const ConfigSection& section)
{
	LoadingBinder binder(section);
	params.declare(binder);
}

template <class Params>
std::vector<ParamInfo> describeParams(Params params)
{
	DescribingBinder binder;
	params.declare(binder);
	return binder.infos;
}

/// Formats a double for INI files and JSON: shortest text that round-trips.
std::string formatNumber(double v);

}  // namespace esif
