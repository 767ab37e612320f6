#pragma once
// Fast text scanning shared by the ASCII readers: std::from_chars on a memory view, no iostream per token.

#include <charconv>
#include <cstdint>
#include <string_view>

namespace pcsketch::io::detail {

/// Parses a whole token as a double (a leading '+' and "nan"/"inf" accepted); false if it is not a number.
inline bool parse_double(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

/// Parses a whole token as an unsigned integer; false if it is not one or overflows.
inline bool parse_uint(std::string_view token, std::uint64_t& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/// Splits a text into lines ('\n' or "\r\n"), counting them from 1.
class LineReader {
 public:
  explicit LineReader(std::string_view text, std::uint64_t first_line = 1) : rest_(text), next_line_(first_line) {}

  /// The next line without its terminator; false at the end of the text.
  bool next(std::string_view& line) {
    if (rest_.empty()) return false;
    const std::size_t eol = rest_.find('\n');
    line = rest_.substr(0, eol);
    rest_ = eol == std::string_view::npos ? std::string_view() : rest_.substr(eol + 1);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    line_ = next_line_++;
    return true;
  }
  std::uint64_t line() const { return line_; }  ///< number of the line last returned
  std::string_view rest() const { return rest_; }
  std::size_t consumed(std::string_view whole) const { return whole.size() - rest_.size(); }

 private:
  std::string_view rest_;
  std::uint64_t next_line_;
  std::uint64_t line_ = 0;
};

/// Splits one line into tokens separated by blanks (and commas/semicolons when `commas` is set).
class Tokens {
 public:
  Tokens(std::string_view line, bool commas) : rest_(line), commas_(commas) {}

  bool next(std::string_view& token) {
    skip_separators();
    if (rest_.empty()) return false;
    std::size_t i = 0;
    while (i < rest_.size() && !separator(rest_[i])) ++i;
    token = rest_.substr(0, i);
    rest_.remove_prefix(i);
    return true;
  }
  bool done() {
    skip_separators();
    return rest_.empty();
  }

 private:
  bool separator(char c) const { return is_space(c) || (commas_ && (c == ',' || c == ';')); }
  void skip_separators() {
    std::size_t i = 0;
    while (i < rest_.size() && separator(rest_[i])) ++i;
    rest_.remove_prefix(i);
  }
  std::string_view rest_;
  bool commas_;
};

/// Tokens across lines (free-form formats: PLY ascii bodies, OFF), skipping '#' comments when asked.
class TokenStream {
 public:
  TokenStream(std::string_view text, std::uint64_t first_line, bool hash_comments)
      : lines_(text, first_line), tokens_({}, false), hash_comments_(hash_comments) {}

  /// The next token; false at the end of the text.
  bool next(std::string_view& token) {
    while (!tokens_.next(token)) {
      std::string_view line;
      if (!lines_.next(line)) return false;
      if (hash_comments_) line = line.substr(0, line.find('#'));
      tokens_ = Tokens(line, false);
    }
    return true;
  }
  std::uint64_t line() const { return lines_.line(); }

 private:
  LineReader lines_;
  Tokens tokens_;
  bool hash_comments_;
};

}  // namespace pcsketch::io::detail
