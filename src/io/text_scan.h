#pragma once
// Fast text scanning shared by the ASCII readers: std::from_chars on a memory view, no iostream per token.

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>

#include "pcsketch/core/error.h"

namespace pcsketch::io::detail {

/// Parses a whole token as a double (a leading '+' and "nan"/"inf" accepted); false if it is not a number.
inline bool parse_double(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

/// Names a token that parse_double rejected: an "out-of-range value" (1e309 overflows a double) or a "non-numeric
/// value", quoted.
inline std::string bad_number(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  double value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  const bool range = ec == std::errc::result_out_of_range && end == token.data() + token.size();
  return (range ? "out-of-range value " : "non-numeric value ") + quote(token);
}

/// Parses a whole token as an unsigned integer; false if it is not one or overflows.
inline bool parse_uint(std::string_view token, std::uint64_t& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/// The text after its UTF-8 byte order mark, if it has one (Windows editors write it).
inline std::string_view skip_bom(std::string_view text) {
  return text.starts_with("\xEF\xBB\xBF") ? text.substr(3) : text;
}

/// Longest line a text reader accepts. No point format needs more; without a limit, a 20 GB file without a newline
/// would be scanned and its "line" copied whole.
inline constexpr std::size_t kMaxLineBytes = std::size_t{1} << 20;

/// Splits a text into lines ending in LF, CRLF or a lone CR (old Mac exports), counting them from 1.
class LineReader {
 public:
  /// `name` stands for the input in the error thrown for a line over kMaxLineBytes.
  explicit LineReader(std::string_view text, std::uint64_t first_line = 1, std::string_view name = "input")
      : text_(text), next_line_(first_line), name_(name) {}

  /// The next line without its terminator; false at the end of the text.
  bool next(std::string_view& line) {
    if (pos_ == text_.size()) return false;
    line_ = next_line_++;
    // LFs are searched for once, never past kMaxLineBytes ahead: an endless line or a CR-only file costs linear time.
    const std::size_t limit = pos_ + std::min(text_.size() - pos_, kMaxLineBytes + 1);
    if (lf_ < pos_ || lf_ == kNone) {
      const std::size_t from = std::max(pos_, searched_);
      const std::size_t found = text_.substr(from, limit - from).find('\n');
      lf_ = found == std::string_view::npos ? kNone : from + found;
      searched_ = lf_ == kNone ? limit : lf_;
    }
    const std::size_t end = lf_ == kNone ? limit : lf_;
    const std::size_t cr = text_.substr(pos_, end - pos_).find('\r');
    std::size_t eol = lf_;
    if (cr != std::string_view::npos && pos_ + cr + 1 != lf_) eol = pos_ + cr;  // a lone CR ends the line
    if (eol == kNone && text_.size() - pos_ > kMaxLineBytes)
      throw Error(FileLoc{std::string(name_), line_, {}},
                  "line longer than " + std::to_string(kMaxLineBytes) + " bytes (not a text point cloud?)");
    if (eol == kNone) eol = text_.size();
    line = text_.substr(pos_, eol - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = std::min(eol + 1, text_.size());
    return true;
  }
  std::uint64_t line() const { return line_; }  ///< number of the line last returned
  std::string_view rest() const { return text_.substr(pos_); }
  std::size_t consumed(std::string_view whole) const { return whole.size() - (text_.size() - pos_); }
  std::size_t offset() const { return pos_; }  ///< bytes of the text read: the lines returned and their ends

 private:
  static constexpr std::size_t kNone = std::string_view::npos;
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t lf_ = kNone;    ///< offset of the next LF at or after pos_, kNone when none before searched_
  std::size_t searched_ = 0;  ///< text before this offset has been searched for LF
  std::uint64_t next_line_;
  std::string_view name_;
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
  TokenStream(std::string_view text, std::uint64_t first_line, bool hash_comments, std::string_view name = "input")
      : lines_(text, first_line, name), tokens_({}, false), hash_comments_(hash_comments) {}

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
  /// The next token of the current line only; false when the line has none left (the line is not left).
  bool next_on_line(std::string_view& token) { return tokens_.next(token); }
  std::uint64_t line() const { return lines_.line(); }
  /// Whether the line of the last token has no token left (an ascii PLY entry is one line).
  bool line_done() { return tokens_.done(); }
  /// Bytes of the text read: every line a token came from, its end included (where a streamed read may release).
  std::size_t offset() const { return lines_.offset(); }

 private:
  LineReader lines_;
  Tokens tokens_;
  bool hash_comments_;
};

}  // namespace pcsketch::io::detail
