// Numbers as text that reads back as exactly the same double: the CSV files, the snapshots'
// parameters and every message that quotes a value use this one form.
#pragma once

#include <cstddef>
#include <string>

namespace marble_maze {

/// Room enough for any double in the form below (at most 24 characters), and for the copies of a
/// fixed 24 bytes that lay it out, which may write past its end.
constexpr std::size_t kExactTextSize = 48;

/// Writes `value` at `first` in the shortest form that reads back exactly, laid out as printf's
/// %g with at least six digits ("0.1", "0.0001", "500000", "1e-05", "-2.5e+158", "inf"; NaN as
/// "nan", whatever its sign), and returns the end. `first` must have kExactTextSize characters
/// of room, all of which it may write.
char* writeExact(char* first, double value);

/// The same as a string.
std::string exactText(double value);

/// Appends the same to `out`.
void appendExact(std::string* out, double value);

}  // namespace marble_maze
