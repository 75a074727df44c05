#pragma once
// The files a run writes (history.csv, the CSVs, ParaView files, summary.json): a write that
// fails throws at once, naming the file and the operating system's reason ("No space left on
// device", "File too large"), where a plain std::ofstream only turns bad and a later check can
// say no more than "write failed" (the reason, errno, is long gone by then).
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace dembridge::dem
{
/// "FILE: cannot write: REASON" for the error number @p error (0: no reason known).
inline std::runtime_error write_error(const std::filesystem::path& file, int error)
{
  return std::runtime_error(file.string() + ": cannot write: " +
                            (error ? std::system_category().message(error) : "I/O error"));
}

namespace detail
{
/// A file buffer that throws write_error when the system refuses its bytes. The stream over it
/// (OutputFile) rethrows that exception from the insertion that wrote them.
class ReportingFileBuf : public std::filebuf
{
public:
  std::filesystem::path file;

protected:
  int_type overflow(int_type c) override
  {
    errno = 0;
    const int_type written = std::filebuf::overflow(c);
    if (traits_type::eq_int_type(written, traits_type::eof()))
      throw write_error(file, errno);
    return written;
  }
  std::streamsize xsputn(const char_type* s, std::streamsize n) override
  {
    errno = 0;
    const std::streamsize written = std::filebuf::xsputn(s, n);
    if (written < n)
      throw write_error(file, errno);
    return written;
  }
  int sync() override
  {
    errno = 0;
    const int result = std::filebuf::sync();
    if (result != 0)
      throw write_error(file, errno);
    return result;
  }
};
} // namespace detail

/// An output file stream: open() and every insertion throw std::runtime_error naming the file and
/// the reason when the system refuses them; close() writes what is buffered and throws likewise.
/// A file left open is closed by the destructor without a check: call close() to know that every
/// byte was written.
class OutputFile : public std::ostream
{
public:
  OutputFile() : std::ostream(nullptr)
  {
    init(&buffer_);
    exceptions(std::ios::badbit); // why: rethrows the buffer's write_error to the writer
  }
  explicit OutputFile(const std::filesystem::path& file,
                      std::ios::openmode mode = std::ios::out | std::ios::trunc)
      : OutputFile()
  {
    open(file, mode);
  }

  void open(const std::filesystem::path& file,
            std::ios::openmode mode = std::ios::out | std::ios::trunc)
  {
    buffer_.file = file;
    errno = 0;
    if (!buffer_.open(file, mode | std::ios::out))
      throw std::runtime_error(file.string() + ": cannot open it for writing: " +
                               std::system_category().message(errno ? errno : EIO));
    clear();
  }

  bool is_open() const { return buffer_.is_open(); }

  /// Writes the buffered bytes and closes the file; throws naming it if any write failed.
  void close()
  {
    if (!buffer_.is_open())
      return;
    flush();
    errno = 0;
    if (!buffer_.close())
      throw write_error(buffer_.file, errno);
  }

private:
  detail::ReportingFileBuf buffer_;
};
} // namespace dembridge::dem
