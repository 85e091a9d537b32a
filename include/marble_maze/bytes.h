// Bytes of a state, for snapshots: values written and read back bit for bit, in order. The
// format is this machine's (doubles as IEEE 754 in its byte order), as a bag recorded and
// replayed on the same kind of machine needs.
#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "marble_maze/geometry.h"

namespace marble_maze {

class ByteWriter {
 public:
  template <typename T>
  void put(const T& value) {
    static_assert(std::is_arithmetic<T>::value, "numbers only");
    const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  void put(const Vec3& v) {
    for (int a = 0; a < 3; ++a) put(v[a]);
  }
  void put(const Mat3& m) {
    for (int i = 0; i < 9; ++i) put(m.data()[i]);
  }
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
};

class ByteReader {
 public:
  explicit ByteReader(const std::vector<std::uint8_t>& bytes) : bytes_(bytes) {}
  template <typename T>
  T get() {
    static_assert(std::is_arithmetic<T>::value, "numbers only");
    if (at_ + sizeof(T) > bytes_.size())
      throw std::runtime_error("snapshot: " + std::to_string(bytes_.size()) +
                               " bytes, too few for a state");
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  Vec3 vec3() {
    Vec3 v;
    for (int a = 0; a < 3; ++a) v[a] = get<double>();
    return v;
  }
  Mat3 mat3() {
    Mat3 m;
    for (int i = 0; i < 9; ++i) m.data()[i] = get<double>();
    return m;
  }
  bool done() const { return at_ == bytes_.size(); }

 private:
  const std::vector<std::uint8_t>& bytes_;
  std::size_t at_ = 0;
};

/// FNV-1a, 64 bits: a state's fingerprint, for determinism tests.
inline std::uint64_t fingerprint(const std::vector<std::uint8_t>& bytes) {
  std::uint64_t hash = 14695981039346656037ull;
  for (std::uint8_t b : bytes) {
    hash ^= b;
    hash *= 1099511628211ull;
  }
  return hash;
}

}  // namespace marble_maze
