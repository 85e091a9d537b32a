#include "marble_maze/exact_text.h"

#include <dragonbox/dragonbox.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace marble_maze {

namespace {
constexpr std::size_t kCopy = 24;  // (a double has at most 17 digits)
}  // namespace

char* writeExact(char* first, double value) {
  if (std::isnan(value)) {  // (its sign says nothing; printf would show "-nan")
    return std::copy_n("nan", 3, first);
  }
  if (std::isinf(value)) return std::copy_n("-inf" + (value > 0), 3 + (value < 0), first);
  char* out = first;
  *out = '-';
  out += std::signbit(value);
  if (value == 0) {
    *out = '0';
    return out + 1;
  }
  // The shortest digits that read back exactly, as a whole number and a power of ten. Dragonbox
  // finds them in a quarter of std::to_chars's time, which a CSV row at every step feels. They
  // are then laid out as %g lays out that many digits, fixed where -4 <= exponent < max(digits,
  // 6): "0.01234", "1234567", else "1.234e-05". The copies are of a fixed kCopy bytes, more than
  // the digits need (a move or three each), which kExactTextSize leaves room for.
  const auto decimal = jkj::dragonbox::to_decimal(value, jkj::dragonbox::policy::sign::ignore);
  char digits[kExactTextSize];
  const int count =
      static_cast<int>(std::to_chars(digits, digits + 20, decimal.significand).ptr - digits);
  const int exponent = decimal.exponent + count - 1;  // of the first digit
  if (exponent < -4 || exponent >= std::max(count, 6)) {
    *out++ = digits[0];
    if (count > 1) {
      *out++ = '.';
      std::memcpy(out, digits + 1, kCopy);
      out += count - 1;
    }
    *out++ = 'e';
    *out++ = exponent < 0 ? '-' : '+';
    int magnitude = std::abs(exponent);
    if (magnitude >= 100) {
      *out++ = static_cast<char>('0' + magnitude / 100);
      magnitude %= 100;
    }
    *out++ = static_cast<char>('0' + magnitude / 10);
    *out++ = static_cast<char>('0' + magnitude % 10);
    return out;
  }
  if (exponent < 0) {  // "0.0" and zeros, then the digits
    std::memset(out, '0', 6);
    out[1] = '.';
    out += 1 - exponent;
    std::memcpy(out, digits, kCopy);
    return out + count;
  }
  std::memcpy(out, digits, kCopy);
  if (count <= exponent + 1) {  // a whole number: the digits, then zeros
    std::memset(out + count, '0', 16);
    return out + exponent + 1;
  }
  out += exponent + 1;  // the digits before the point are in place; the point, then the rest
  *out++ = '.';
  std::memcpy(out, digits + exponent + 1, kCopy);
  return out + count - 1 - exponent;
}

std::string exactText(double value) {
  char text[kExactTextSize];
  return std::string(text, writeExact(text, value));
}

void appendExact(std::string* out, double value) {
  char text[kExactTextSize];
  out->append(text, writeExact(text, value));
}

}  // namespace marble_maze
