#include "core/input/number_format.h"

#include <cctype>
#include <string_view>

namespace sable {

std::string number_format_problem(const std::string& fmt, bool integer) {
  int conversions = 0;
  for (std::size_t i = 0; i < fmt.size(); ++i) {
    if (fmt[i] != '%') continue;
    if (i + 1 < fmt.size() && fmt[i + 1] == '%') {
      ++i;
      continue;
    }
    std::size_t k = i + 1;
    while (k < fmt.size() && std::string_view("-+ #0").find(fmt[k]) != std::string_view::npos) ++k;
    auto digits = [&] {
      const std::size_t b = k;
      while (k < fmt.size() && std::isdigit(static_cast<unsigned char>(fmt[k]))) ++k;
      return k - b;
    };
    bool wide = digits() > 3;
    if (k < fmt.size() && fmt[k] == '.') ++k, wide = wide || digits() > 3;
    if (wide) return "width and precision of at most three digits each";
    if (integer) while (k < fmt.size() && fmt[k] == 'l') ++k;
    else if (k < fmt.size() && fmt[k] == 'l') ++k;  // %lf means %f
    if (k >= fmt.size()) return "a conversion letter after '%'";
    const char c = fmt[k];
    const std::string_view ok = integer ? "di" : "eEfFgGaA";
    if (ok.find(c) == std::string_view::npos)
      return std::string("one ") + (integer ? "%d" : "%e, %f or %g") + " conversion, not '" + fmt.substr(i, k - i + 1) + "'";
    ++conversions;
    i = k;
  }
  if (conversions != 1)
    return std::string("exactly one ") + (integer ? "%d" : "%e, %f or %g") + " conversion (found " + std::to_string(conversions) + ")";
  return "";
}

}  // namespace sable
