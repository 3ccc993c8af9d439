#include "scenes/toml_guard.hpp"

#include <cctype>
#include <string>
#include <vector>

namespace fetic::scenes {
namespace {

// Counts the levels toml++ recurses on, from the structure characters the lexer below
// passes it (everything outside strings and comments but white space) and the starts of
// strings. Levels: the root table is 0; a header segment counts 2 (an array of tables adds
// a table inside an array at each of its segments), a key segment 1, an array or an inline
// table 1. Over-counting is harmless: a scene nests 4 deep.
class NestingCounter {
 public:
  // The line where the nesting first went deeper than kMaxNesting, or 0.
  int deepest_line() const { return deepest_line_; }

  void newline() {
    if (containers_.empty()) mode_ = Mode::LineStart;
  }
  // A quoted string starts: a key segment, or a value to skip.
  void string_start(int line) {
    if (mode_ == Mode::LineStart) start_key(header_depth_);
    if (mode_ != Mode::Value) segment(line);
  }
  // A structure character; `doubled` when the next character is the same ("[[", "]]").
  void structure(char c, bool doubled, int line) {
    if (skip_next_) {
      skip_next_ = false;
      return;
    }
    switch (mode_) {
      case Mode::LineStart:
        if (c == '[') {
          mode_ = Mode::Header;
          header_depth_ = 0;
          segment_open_ = false;
          skip_next_ = doubled;
          return;
        }
        start_key(header_depth_);
        key(c, line);
        return;
      case Mode::Key:
        key(c, line);
        return;
      case Mode::Header:
        if (c == '.') {
          segment_open_ = false;
        } else if (c == ']') {
          skip_next_ = doubled;
          mode_ = Mode::LineStart;
        } else {
          segment(line);
        }
        return;
      case Mode::Value:
        value(c, line);
        return;
    }
  }

 private:
  enum class Mode { LineStart, Header, Key, Value };
  struct Container {
    char kind;
    int outer;  // the depth of the value that holds it
  };

  void check(int depth, int line) {
    if (depth > kMaxNesting && deepest_line_ == 0) deepest_line_ = line;
  }
  void start_key(int base) {
    mode_ = Mode::Key;
    key_depth_ = base;
    segment_open_ = false;
  }
  // A key or header segment starts at a bare character or a quoted key.
  void segment(int line) {
    if (segment_open_) return;
    segment_open_ = true;
    if (mode_ == Mode::Header) {
      header_depth_ += 2;
      check(header_depth_, line);
    } else {
      ++key_depth_;
      check(key_depth_, line);
    }
  }
  void key(char c, int line) {
    if (c == '.') {
      segment_open_ = false;
    } else if (c == '=') {
      mode_ = Mode::Value;
      value_depth_ = key_depth_;
    } else if (c == '}' && !containers_.empty()) {  // an empty inline table
      value_depth_ = containers_.back().outer;
      containers_.pop_back();
      mode_ = Mode::Value;
    } else {
      segment(line);
    }
  }
  void value(char c, int line) {
    if (c == '[' || c == '{') {
      containers_.push_back({c, value_depth_});
      ++value_depth_;  // the elements of an array, the keys of an inline table
      check(value_depth_, line);
      if (c == '{') start_key(value_depth_);
    } else if (c == ']' || c == '}') {
      if (!containers_.empty()) {
        value_depth_ = containers_.back().outer;
        containers_.pop_back();
      }
    } else if (c == ',' && !containers_.empty() && containers_.back().kind == '{') {
      start_key(containers_.back().outer + 1);
    }
  }

  Mode mode_ = Mode::LineStart;
  std::vector<Container> containers_;
  int header_depth_ = 0;
  int key_depth_ = 0, value_depth_ = 0;
  bool segment_open_ = false;
  bool skip_next_ = false;  // the second bracket of "[[" or "]]" in a header
  int deepest_line_ = 0;
};

// Delimits strings and comments as toml++ 3.3 does (a quote inside a bare word starts no
// string there), stops at a NUL byte or a non-ASCII character outside strings and comments,
// and passes everything else to the nesting counter.
class Lexer {
 public:
  explicit Lexer(std::string_view text) : text_(text) {}

  Problem run() {
    for (size_t i = 0; i < text_.size(); ++i) {
      const char c = text_[i];
      if (c == '\0') return {line_, "TOML syntax error: a NUL byte (not a text file?)"};
      const bool ascii = static_cast<unsigned char>(c) < 0x80;
      if (c == '\n') ++line_;
      const char* problem = nullptr;
      switch (state_) {
        case State::Normal:
          problem = normal(i, c, ascii);
          break;
        case State::Comment:
          if (c == '\n') end_of_line_outside();
          break;
        case State::Basic:
          if (c == '\\' && i + 1 < text_.size() && text_[i + 1] != '\n')
            ++i;  // an escaped character
          else if (c == '"' || c == '\n')
            end_of_one_line_string(c);
          break;
        case State::Literal:
          if (c == '\'' || c == '\n') end_of_one_line_string(c);
          break;
        case State::MultiBasic:
          problem = multi_basic(i, c, ascii);
          break;
        case State::MultiLiteral:
          if (starts(i, "'''")) end_of_multi_line_string(i, '\'');
          break;
      }
      if (problem)
        return {line_, std::string("TOML syntax error: a non-ASCII character ") + problem};
      if (nesting_.deepest_line() > 0)
        return {nesting_.deepest_line(),
                "the TOML nests deeper than " + std::to_string(kMaxNesting) +
                    " levels (table headers, dotted keys, arrays and inline tables together; "
                    "a scene needs 4)"};
    }
    return {0, ""};
  }

 private:
  enum class State { Normal, Comment, Basic, Literal, MultiBasic, MultiLiteral };

  bool starts(size_t i, std::string_view what) const {
    return text_.substr(i, what.size()) == what;
  }
  void end_of_line_outside() {
    state_ = State::Normal;
    in_word_ = false;
    if (depth_ == 0) value_ = false;
    nesting_.newline();
  }
  void end_of_one_line_string(char c) {
    state_ = State::Normal;
    in_word_ = true;  // a quote right after a string starts none
    if (c == '\n') {
      if (depth_ == 0) value_ = false;
      nesting_.newline();
    }
  }
  void end_of_multi_line_string(size_t& i, char quote) {
    state_ = State::Normal;
    i += 2;
    for (int extra = 0; extra < 2 && i + 1 < text_.size() && text_[i + 1] == quote; ++extra)
      ++i;  // up to 2 quotes before the end
    in_word_ = true;
  }

  // Outside strings and comments.
  const char* normal(size_t& i, char c, bool ascii) {
    if (!ascii) return "outside a string or comment";
    if (c == '\n') {
      end_of_line_outside();
      return nullptr;
    }
    if (c == '#') {
      state_ = State::Comment;
      in_word_ = false;
      return nullptr;
    }
    if (c == ' ' || c == '\t' || c == '\r') {
      in_word_ = false;
      return nullptr;
    }
    const bool doubled = i + 1 < text_.size() && text_[i + 1] == c;
    if (c == '"' || c == '\'') {
      if (in_word_) {  // in a bare word (0"x, a."b") toml++ scans on through the quote
        nesting_.structure(c, doubled, line_);
        return nullptr;
      }
      const bool triple = starts(i, c == '"' ? "\"\"\"" : "'''");
      state_ = c == '"' ? (triple ? State::MultiBasic : State::Basic)
                        : (triple ? State::MultiLiteral : State::Literal);
      nesting_.string_start(line_);
      if (triple) i += 2;
      return nullptr;
    }
    nesting_.structure(c, doubled, line_);
    track_value(c);
    return nullptr;
  }

  // Where a value is and whether a bare word goes on (for the quote rule above).
  void track_value(char c) {
    if (c == ',' || c == ']' || c == '}') {  // toml++'s value terminators
      in_word_ = false;
      if (value_ && (c == ']' || c == '}') && depth_ > 0) --depth_;
    } else if (!value_) {  // keys and table headers
      if (c == '=') {
        value_ = true;
        depth_ = 0;
        in_word_ = false;
      } else {
        in_word_ = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
      }
    } else if (!in_word_ && (c == '[' || c == '{')) {
      ++depth_;
    } else if (in_word_ || c != '=') {  // '=' between words: key = value in an inline table
      in_word_ = true;
    }
  }

  // Inside a multi-line basic string: what follows a backslash.
  const char* multi_basic(size_t& i, char c, bool ascii) {
    if (continuation_) {
      if (c == ' ' || c == '\t' || c == '\r' || c == '\n') return nullptr;
      if (!ascii) return "right after a line-ending backslash in a multi-line string";
      continuation_ = false;
    }
    if (c == '\\') {
      size_t j = i + 1;
      while (j < text_.size() && (text_[j] == ' ' || text_[j] == '\t' || text_[j] == '\r'))
        ++j;
      if (j < text_.size() && static_cast<unsigned char>(text_[j]) >= 0x80)
        return "after a backslash in a multi-line string";
      if (j < text_.size() && text_[j] == '\n')
        continuation_ = true;
      else if (i + 1 < text_.size())
        ++i;  // an escaped character
    } else if (starts(i, "\"\"\"")) {
      end_of_multi_line_string(i, '"');
    }
    return nullptr;
  }

  std::string_view text_;
  NestingCounter nesting_;
  State state_ = State::Normal;
  int line_ = 1;
  bool continuation_ = false;  // after a line-ending backslash in a multi-line basic string
  // Outside strings and comments: in a value (after '=', until the end of the line outside
  // brackets), brackets open there, and inside a bare word (key, number, date, ...).
  bool value_ = false;
  int depth_ = 0;
  bool in_word_ = false;
};

}  // namespace

Problem toml_guard_problem(std::string_view text) {
  return Lexer(text).run();
}

}  // namespace fetic::scenes
