#pragma once
// A fast line/token scanner over an in-memory text file (used by the OBJ, OFF, PLY-ASCII and STL-ASCII readers).
#include <charconv>
#include <string_view>

namespace quadcover {

class TextScanner {
 public:
  explicit TextScanner(std::string_view text) : text_(text) {}  ///< \pre text outlives the scanner.

  /// Advances to the next line; false at the end. Comments (`#` to end of line) are stripped. \pre none
  bool next_line() {
    if (pos_ >= text_.size()) return false;
    const std::size_t end = text_.find('\n', pos_);
    const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
    cur_ = text_.substr(pos_, stop - pos_);
    if (const std::size_t hash = cur_.find('#'); hash != std::string_view::npos) cur_ = cur_.substr(0, hash);
    pos_ = stop + 1;
    ++line_;
    return true;
  }

  /// The next whitespace-separated token of the current line, or "" at its end. \pre none
  std::string_view token() {
    std::size_t i = 0;
    while (i < cur_.size() && is_space(cur_[i])) ++i;
    std::size_t j = i;
    while (j < cur_.size() && !is_space(cur_[j])) ++j;
    const std::string_view tok = cur_.substr(i, j - i);
    cur_ = cur_.substr(j);
    return tok;
  }

  /// Parses the next token as a double (accepts nan/inf, which validation reports later). \pre none
  bool number(double& out) {
    const std::string_view tok = token();
    if (tok.empty()) return false;
    const char* first = tok.data();
    if (*first == '+') ++first;
    const auto [ptr, ec] = std::from_chars(first, tok.data() + tok.size(), out);
    return ec == std::errc() && ptr == tok.data() + tok.size();
  }

  /// \pre none
  template <class Int>
  bool integer(Int& out) {
    const std::string_view tok = token();
    if (tok.empty()) return false;
    const auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), out);
    return ec == std::errc() && ptr == tok.data() + tok.size();
  }

  /// True if the rest of the current line holds no more tokens. \pre none
  bool at_line_end() {
    for (char c : cur_)
      if (!is_space(c)) return false;
    return true;
  }

  long line() const { return line_; }  ///< \pre none
  std::string_view rest() const { return cur_; }  ///< \pre none
  std::size_t offset() const { return pos_; }  ///< \pre none

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
  std::string_view text_;
  std::string_view cur_;
  std::size_t pos_ = 0;
  long line_ = 0;
};

}  // namespace quadcover
