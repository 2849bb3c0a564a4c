#pragma once
#include <string>

namespace sable {

// A printf format given by a deck ($(expr:%fmt), thermo_modify format, dump_modify
// format of dump local): empty when it has exactly one conversion of the expected kind
// (e/f/g... or, for integer, d/i) and nothing snprintf would read beyond the one number
// (%s, %n, '*'); otherwise what is wrong.
std::string number_format_problem(const std::string& fmt, bool integer);

}  // namespace sable
