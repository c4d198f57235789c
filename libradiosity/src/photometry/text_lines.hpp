// Reading photometric text with line numbers (internal header): lines split on LF, CR LF or
// CR; numbers as whole tokens (blanks or commas between), so "12x" or "1.2.3" is refused.
#pragma once
#include "radiosity/error.hpp"

#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rad::photometry {

// A quoted prefix of a line for a message: never the whole of a huge line.
std::string quoted(std::string_view text);

// The text without a UTF-8 byte-order mark (a spreadsheet's "CSV UTF-8" starts with one);
// InputError naming `name` for UTF-16 or UTF-32 text (a byte-order mark of those, or NUL
// bytes): the readers read ASCII and UTF-8.
std::string_view plain_text(std::string_view text, const std::string& name);

// The text's lines without their line ends.
std::vector<std::string_view> split_lines(std::string_view text);

// The fields of one CSV line, blanks around each trimmed (double quotes around a field allow
// commas in it; "" inside them is one quote).
std::vector<std::string> csv_fields(std::string_view line);

// Whether a double quote is left open at the end of `text` (a quoted field going on past the
// line end, as spreadsheets write a cell holding a line break): its quotes are odd.
bool csv_quote_open(std::string_view text);
// The message for a quote still open at the end of the file, at the line it opened on.
[[noreturn]] void unclosed_csv_quote(const FileLoc& opened);

// A finite number that is the whole of `token`, or false.
bool parse_number(std::string_view token, double& value);

// Numbers read token by token across lines, each knowing its line.
class TokenCursor {
  public:
    TokenCursor(std::vector<std::string_view> lines, std::size_t first_line, std::string file);
    // The next number; `what` names it in the error when it is missing or not a number.
    double number(const std::string& what);
    // A number that must be a whole count within [low, high].
    long count(const std::string& what, long low, long high);
    bool at_end();
    // The line of the last token read (past the end: the last line).
    FileLoc where() const {
        const auto last = lines_.empty() ? 0 : lines_.size() - 1;
        return {file_, static_cast<int>(std::min(line_, last) + 1)};
    }
    [[noreturn]] void fail(const std::string& message) const;

  private:
    bool next_token(std::string_view& token);
    std::vector<std::string_view> lines_;
    std::size_t line_;
    std::size_t pos_ = 0;
    std::string file_;
};

// The brightest intensity a file may give, far past any luminaire's (a stadium floodlight's
// is about 1e6 cd): a larger one is a wrong multiplier, and past it products overflow.
inline constexpr double kMaxCandela = 1e12;
// A TILT multiplier scales the output with the lamp's tilt, around 1: past this, a typo.
inline constexpr double kMaxTiltFactor = 10;

// `value` (as the file gives it) times `scale` (its multipliers): refused at the cursor's
// line when that is not finite or above kMaxCandela, naming both.
double checked_candela(double value, double scale, const TokenCursor& in);

} // namespace rad::photometry
