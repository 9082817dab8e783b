#pragma once
/// \file WholeReadStream.h
/// The stream MRPT deserialises a rawlog from. MRPT 2.5 reads a value of a
/// simple type (`CArchive& operator>>(CArchive&, T&)`) with
/// CArchive::ReadBuffer and ignores how many bytes came back; ReadBuffer
/// throws only when none did. A value cut by the end of the data (a count
/// of two bytes where four belong) is thus left partly as it was: in
/// CObservationBearingRange::serializeFrom that is the local `uint32_t n`,
/// uninitialised, then used as the number of measurements to allocate and
/// read, so the same file read twice gave different answers. This stream
/// hands out every byte asked for or none: a value is read whole, or MRPT
/// meets the end of the data it reports as such, and the stream remembers
/// that the data ended inside a value (CMemoryStream cannot be moved to its
/// end: its Seek from the end stops one byte short).

#include <mrpt/io/CMemoryStream.h>

namespace esif
{
class WholeReadStream : public mrpt::io::CMemoryStream
{
   public:
	size_t Read(void* buffer, size_t count) override
	{
		if (count > getTotalBytesCount() - getPosition())
		{
			ended_inside_value_ = true;	 // nothing of a value the data does not hold whole
			return 0;
		}
		return CMemoryStream::Read(buffer, count);
	}

	/// Whether a read asked for more than was left: the data ends inside a value.
	bool endedInsideValue() const { return ended_inside_value_; }

   private:
	bool ended_inside_value_ = false;
};

}  // namespace esif
