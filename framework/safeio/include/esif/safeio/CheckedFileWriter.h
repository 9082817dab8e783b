#pragma once
/// \file CheckedFileWriter.h
/// A file written piece by piece with every step checked (each write, then
/// fsync and close), for outputs too large to hold in memory first: the
/// streaming counterpart of writeBytesAtomically's checked write. Use it on
/// the temporary path writeAtomically (AtomicFile.h) hands out.

#include <cstddef>
#include <string>

namespace esif
{
class CheckedFileWriter
{
   public:
	/// Creates or truncates `path`. Errors name `shown_name`, the name the
	/// user knows the file by (the final name when `path` is a temporary one).
	CheckedFileWriter(const std::string& path, std::string shown_name);
	/// Closes the file if finish() was not called (an error path: the
	/// caller's writeAtomically removes the temporary file).
	~CheckedFileWriter();
	CheckedFileWriter(const CheckedFileWriter&) = delete;
	CheckedFileWriter& operator=(const CheckedFileWriter&) = delete;

	/// Appends `size` bytes; throws InputError "`shown_name`: cannot write
	/// (write): <errno text>" on failure.
	void write(const void* data, std::size_t size);
	/// fsyncs and closes the file, both checked (a full disk may show only here).
	void finish();
	/// The name errors give the file.
	const std::string& shownName() const { return shown_name_; }

   private:
	int fd_ = -1;
	std::string shown_name_;
};

}  // namespace esif
