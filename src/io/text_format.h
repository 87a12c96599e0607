#pragma once
// Number formatting for the text writers: shortest representation that reads back to the same double
// (std::to_chars), so a write/read round trip is exact. Internal to src/io.
#include <charconv>
#include <cstdint>
#include <ostream>
#include <string>

namespace quadcover::detail {

/// An output buffer that flushes to a stream in large blocks (much faster than operator<< per number). Every member:
/// \pre none; the stream's own failure state is the caller's to check after flush().
class TextBuffer {
 public:
  explicit TextBuffer(std::ostream& out) : out_(out) { buf_.reserve(kBlock + 256); }
  ~TextBuffer() = default;
  TextBuffer(const TextBuffer&) = delete;
  TextBuffer& operator=(const TextBuffer&) = delete;

  TextBuffer& put(std::string_view s) {
    buf_.append(s);
    return maybe_flush();
  }
  TextBuffer& put(char c) {
    buf_.push_back(c);
    return maybe_flush();
  }
  /// Shortest round-trip decimal form of x ("nan", "inf", "-inf" for non-finite values).
  TextBuffer& num(double x) {
    char tmp[32];
    const auto res = std::to_chars(tmp, tmp + sizeof tmp, x);
    buf_.append(tmp, res.ptr);
    return maybe_flush();
  }
  TextBuffer& num(std::int64_t i) {
    char tmp[24];
    const auto res = std::to_chars(tmp, tmp + sizeof tmp, i);
    buf_.append(tmp, res.ptr);
    return maybe_flush();
  }
  TextBuffer& num(int i) { return num(static_cast<std::int64_t>(i)); }
  /// Writes what is buffered; call once at the end.
  void flush() {
    out_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
    buf_.clear();
  }

 private:
  static constexpr std::size_t kBlock = 1 << 16;
  TextBuffer& maybe_flush() {
    if (buf_.size() >= kBlock) flush();
    return *this;
  }
  std::ostream& out_;
  std::string buf_;
};

}  // namespace quadcover::detail
