#pragma once
// Text helpers of the tests that read written pages and reports.
#include <string>

namespace quadcover::testing {

/// The text of `s` between the first `open` and the next `close` after it ("" without `open`).
inline std::string between(const std::string& s, const std::string& open, const std::string& close) {
  const auto a = s.find(open);
  if (a == std::string::npos) return "";
  const auto b = s.find(close, a + open.size());
  return s.substr(a + open.size(), b - a - open.size());
}

}  // namespace quadcover::testing
