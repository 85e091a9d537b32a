#include "marble_maze/exact_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>

namespace marble_maze {

char* writeExact(char* first, double value) {
  if (std::isnan(value)) {  // (its sign says nothing; printf would show "-nan")
    return std::copy_n("nan", 3, first);
  }
  if (std::isinf(value)) return std::copy_n("-inf" + (value > 0), 3 + (value < 0), first);
  // The shortest digits that read back exactly, in one call, as "d.ddde-XX". They are then laid
  // out as %g lays out that many digits, fixed where -4 <= exponent < max(digits, 6): "0.01234",
  // "1234567". (to_chars's own general form costs a fifth more, and still writes "1.234567e+06".)
  // The copies are of a fixed 16 bytes, more than the digits need (a move or two each), which
  // kExactTextSize leaves room for.
  char text[kExactTextSize + 16];
  const char* end =
      std::to_chars(text, text + kExactTextSize, value, std::chars_format::scientific).ptr;
  const char* e = end[-4] == 'e' ? end - 4 : end - 5;  // (two or three digits: "e+06", "e-300")
  int exponent = 0;
  for (const char* digit = e + 2; digit != end; ++digit) exponent = exponent * 10 + (*digit - '0');
  if (e[1] == '-') exponent = -exponent;
  const bool negative = text[0] == '-';
  const char* digits = text + negative;  // "d.ddd" or "d"
  const int count = static_cast<int>(e - digits) - (digits[1] == '.');
  if (exponent < -4 || exponent >= std::max(count, 6)) {
    std::memcpy(first, text, kExactTextSize);
    return first + (end - text);
  }
  char* out = first;
  *out = '-';
  out += negative;
  if (exponent < 0) {  // "0.0" and zeros, then the digits
    std::memset(out, '0', 6);
    out[1] = '.';
    out += 1 - exponent;
    *out++ = digits[0];
    std::memcpy(out, digits + 2, 16);
    return out + count - 1;
  }
  *out++ = digits[0];
  std::memcpy(out, digits + 2, 16);
  if (count <= exponent + 1) {  // a whole number: the digits, then zeros
    std::memset(out + count - 1, '0', 16);
    return out + exponent;
  }
  out += exponent;  // the digits before the point are in place; the point, then the rest
  *out++ = '.';
  std::memcpy(out, digits + 2 + exponent, 16);
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
