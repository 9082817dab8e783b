/// \file RawlogDigest.cpp
/// See RawlogDigest.h.

#include "RawlogDigest.h"

#include <stdexcept>
#include <zlib.h>

namespace esif
{
namespace
{
/// Feeds values to a running CRC-32 as their bytes.
class Crc
{
   public:
	Crc() = default;
	explicit Crc(std::uint32_t running) : crc_(running) {}
	template <class T>
	void add(const T& value)
	{
		crc_ = ::crc32(crc_, reinterpret_cast<const Bytef*>(&value), sizeof(T));
	}
	void addMatrix(const double* data, std::size_t count)
	{
		crc_ = ::crc32(crc_, reinterpret_cast<const Bytef*>(data), static_cast<uInt>(count * sizeof(double)));
	}
	std::uint32_t value() const { return static_cast<std::uint32_t>(crc_); }

   private:
	uLong crc_ = ::crc32(0L, Z_NULL, 0);
};

void addScan(Crc& crc, const Scan& scan)
{
	crc.add(scan.sensor_on_robot.x());
	crc.add(scan.sensor_on_robot.y());
	crc.add(scan.sensor_on_robot(2));
	crc.add(scan.max_range_m);
	crc.add(scan.fov_rad);
	crc.add(scan.measurements.size());
	for (const RangeBearing& m : scan.measurements)
	{
		crc.add(m.range_m);
		crc.add(m.bearing_rad);
		crc.addMatrix(m.cov.data(), 4);
		crc.add(m.id.value_or(-1));
	}
}

void addStep(Crc& crc, const StepInput& step)
{
	crc.add(step.index);
	crc.add(step.time_s);
	crc.add(step.odometry.has_value());
	if (step.odometry)
	{
		crc.add(step.odometry->delta.x());
		crc.add(step.odometry->delta.y());
		crc.add(step.odometry->delta(2));
		crc.addMatrix(step.odometry->cov.data(), 9);
	}
	crc.add(step.scan.has_value());
	if (step.scan) addScan(crc, *step.scan);
}
}  // namespace

std::uint32_t digestOf(const Rawlog& log)
{
	// The steps and their IDs were summed as the read ended
	// (RawlogSource::steps_digest); the times normalised since are a function
	// of them.
	if (!log.source) throw std::logic_error("digestOf: a rawlog read without its steps' digest");
	Crc crc(log.source->steps_digest);
	crc.add(log.stepCount());
	crc.add(log.truncation_warning.has_value());
	crc.add(log.measurement_count);
	return crc.value();
}

StepsDigest::StepsDigest() : crc_(Crc().value()) {}

void StepsDigest::add(const StepInput& step, const std::vector<std::optional<LandmarkId>>& ids)
{
	Crc crc(crc_);
	addStep(crc, step);
	crc.add(ids.size());
	for (const auto& id : ids) crc.add(id.value_or(-1));
	crc_ = crc.value();
}

}  // namespace esif
