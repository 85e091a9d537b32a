#include "marble_maze/exact_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace marble_maze {

char* writeExact(char* first, double value) {
  if (std::isnan(value)) {  // (its sign says nothing; printf would show "-nan")
    return std::copy_n("nan", 3, first);
  }
  // The shortest digits that read back exactly, from std::to_chars in scientific form
  // ("[-]d[.ddd]e±XX", or "inf"), laid out as printf's %g lays out that many digits (six at
  // least): fixed unless the exponent is below -4 or not below the digits' count, so that a
  // message says "0.0001" and "500000" rather than "1e-04" and "5e+05".
  char* end =
      std::to_chars(first, first + kExactTextSize, value, std::chars_format::scientific).ptr;
  const char* e = std::find(first, end, 'e');
  if (e == end) return end;  // inf
  int exponent = 0;
  std::from_chars(e + (e[1] == '+' ? 2 : 1), end, exponent);
  const bool negative = first[0] == '-';
  char digits[kExactTextSize];
  int count = 0;
  for (const char* p = first + negative; p < e; ++p)
    if (*p != '.') digits[count++] = *p;
  if (exponent < -4 || exponent >= std::max(count, 6)) return end;
  char* out = first + negative;
  if (exponent < 0) {
    *out++ = '0';
    *out++ = '.';
    out = std::fill_n(out, -exponent - 1, '0');
    return std::copy(digits, digits + count, out);
  }
  for (int i = 0; i <= exponent; ++i) *out++ = i < count ? digits[i] : '0';
  if (count > exponent + 1) {
    *out++ = '.';
    out = std::copy(digits + exponent + 1, digits + count, out);
  }
  return out;
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
