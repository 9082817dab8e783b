#pragma once
/// \file RawlogDigest.h
/// A checksum of what a rawlog was read into: the sandboxed child reports it
/// for the read it vouches for, and the reader in esif must come to the same
/// (RawlogReader.cpp), so one read decides what the file holds.

#include <esif/formats/RawlogReader.h>

#include <cstdint>

namespace esif
{
/// CRC-32 (zlib) of what one read gave: the digest of its steps
/// (RawlogSource::steps_digest: each step's index, time, odometry, scan and
/// the IDs as stored), their number, the measurement count and whether the
/// file was cut. std::logic_error for a Rawlog without a source digest.
std::uint32_t digestOf(const Rawlog& log);

/// CRC-32 over steps added one at a time as they are read (each step's
/// index, time, odometry and scan, then the IDs of its measurements as
/// stored): tells whether a second read of a file gave the steps of the
/// first (RawlogSource::steps_digest).
class StepsDigest
{
   public:
	StepsDigest();
	void add(const StepInput& step, const std::vector<std::optional<LandmarkId>>& ids);
	std::uint32_t value() const { return crc_; }

   private:
	std::uint32_t crc_;
};

}  // namespace esif
