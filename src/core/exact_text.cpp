#include "marble_maze/exact_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace marble_maze {

char* writeExact(char* first, double value) {
  if (std::isnan(value)) {  // (its sign says nothing; printf would show "-nan")
    return std::copy_n("nan", 3, first);
  }
  // The shortest digits that read back exactly, in one call. libstdc++ lays them out as %g with
  // six digits' precision: a whole number of seven digits or more, or one with more than six
  // digits in all, comes out as "1.234567e+06". A message reads better with "1234567", so where
  // the exponent is below the digits' count (or below six) the number is laid out fixed, as %g
  // lays out that many digits.
  char* end = std::to_chars(first, first + kExactTextSize, value, std::chars_format::general).ptr;
  char* e = end - 4;  // (an exponent has two or three digits: "e+06", "e-300")
  if (end - first < 5 || (*e != 'e' && *--e != 'e')) return end;  // fixed already, or inf
  int exponent = 0;
  std::from_chars(e + (e[1] == '+' ? 2 : 1), end, exponent);
  char* digits = first + (first[0] == '-');
  const int count = static_cast<int>(e - digits) - (digits[1] == '.');
  if (exponent < 0 || exponent >= std::max(count, 6)) return end;
  char* last = std::remove(digits, e, '.');
  if (count <= exponent + 1) return std::fill_n(last, exponent + 1 - count, '0');
  std::copy_backward(digits + exponent + 1, last, last + 1);
  digits[exponent + 1] = '.';
  return last + 1;
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
