// Little helpers for the checkpoint format: raw little-endian values and arrays, bounds-checked
// on reading (a truncated or foreign file is a clear SetupError, never a crash), and sealed by a
// checksum of every byte before it, so that a file damaged after it was written (a flipped bit, a
// value edited in place) is refused before a single value of it is used.
#pragma once
#include <engine/errors.hpp>

#include <cstdint>
#include <cstring>
#include <fmt/format.h>
#include <string>
#include <type_traits>
#include <vector>

namespace spreadmap::engine {

// 64-bit FNV-1a: enough to tell a damaged file from an intact one (not an adversary's forgery).
inline std::uint64_t checksum(const char *data, std::size_t n) {
  std::uint64_t h = 14695981039346656037ull;
  for (std::size_t i = 0; i < n; ++i) h = (h ^ static_cast<unsigned char>(data[i])) * 1099511628211ull;
  return h;
}

class BinaryWriter {
 public:
  template <class T> void value(const T &v) {
    static_assert(std::is_trivially_copyable_v<T>);
    buf_.append(reinterpret_cast<const char *>(&v), sizeof v);
  }
  template <class T> void array(const std::vector<T> &v) {
    value<std::uint64_t>(v.size());
    buf_.append(reinterpret_cast<const char *>(v.data()), v.size() * sizeof(T));
  }
  const std::string &bytes() const { return buf_; }
  // The bytes followed by their checksum: what BinaryReader::sealed reads.
  std::string sealed() const {
    std::string out = buf_;
    const std::uint64_t sum = checksum(buf_.data(), buf_.size());
    out.append(reinterpret_cast<const char *>(&sum), sizeof sum);
    return out;
  }

 private:
  std::string buf_;
};

class BinaryReader {
 public:
  BinaryReader(std::string bytes, std::string name) : buf_(std::move(bytes)), name_(std::move(name)) {}
  // A reader of what BinaryWriter::sealed wrote: the checksum is checked and taken off first.
  static BinaryReader sealed(std::string bytes, std::string name) {
    BinaryReader r(std::move(bytes), std::move(name));
    const std::size_t n = r.buf_.size();
    if (n < sizeof(std::uint64_t)) r.fail("no checksum: the file is truncated");
    std::uint64_t stored;
    std::memcpy(&stored, r.buf_.data() + n - sizeof stored, sizeof stored);
    r.buf_.resize(n - sizeof stored);
    if (checksum(r.buf_.data(), r.buf_.size()) != stored)
      throw SetupError(fmt::format("{}: damaged: its checksum does not match its content (the file changed after "
                                   "it was written)",
                                   r.name_));
    return r;
  }
  template <class T> T value() {
    T v;
    need(sizeof v);
    std::memcpy(&v, buf_.data() + pos_, sizeof v);
    pos_ += sizeof v;
    return v;
  }
  template <class T> void array(std::vector<T> &v) {
    const auto n = value<std::uint64_t>();
    if (n > buf_.size()) fail("an array length larger than the file");
    need(n * sizeof(T));
    v.resize(n);
    if (n > 0) std::memcpy(v.data(), buf_.data() + pos_, n * sizeof(T));  // an empty vector's data() may be null
    pos_ += n * sizeof(T);
  }
  bool at_end() const { return pos_ == buf_.size(); }
  [[noreturn]] void fail(const std::string &what) const {
    throw SetupError(
        fmt::format("{}: not a valid checkpoint ({} at byte {}); it may be truncated or from another "
                    "version: delete it to start the case afresh",
                    name_, what, pos_));
  }

 private:
  void need(std::size_t n) const {
    if (buf_.size() - pos_ < n) fail("unexpected end of file");
  }
  std::string buf_;
  std::string name_;
  std::size_t pos_ = 0;
};

}  // namespace spreadmap::engine
