#pragma once
// Integers from outside data (PLY counts and indices, JSON settings, text fields)
// arrive as doubles or text. Converting a double that does not fit to an integer
// type is undefined behaviour, so the range is checked first, in double.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

namespace keyturn {

// v as a T in [lo, hi]; nothing when v is NaN, has a fraction or lies outside.
template <typename T>
std::optional<T> integerIn(double v, T lo, T hi) {
  static_assert(std::is_integral_v<T>);
  // 2^digits is the first value past T's maximum and exact in double (T's maximum
  // itself may not be: INT64_MAX rounds up to 2^63).
  const double end = std::ldexp(1.0, std::numeric_limits<T>::digits);
  const double begin = std::is_signed_v<T> ? -end : 0.0;
  if (!(v >= begin && v < end) || v != std::floor(v)) return std::nullopt;
  const T t = static_cast<T>(v);
  if (t < lo || t > hi) return std::nullopt;
  return t;
}

// Text that is exactly a decimal integer in [lo, hi] ("+" and spaces refused).
template <typename T>
std::optional<T> parseIntegerIn(std::string_view s, T lo, T hi) {
  static_assert(std::is_integral_v<T>);
  T v{};
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size() || v < lo || v > hi) return std::nullopt;
  return v;
}

// A double from outside data as text for an error message, whatever its size
// (std::to_string(static_cast<long long>(v)) is the undefined behaviour above).
inline std::string numberText(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}

}  // namespace keyturn
