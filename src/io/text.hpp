// actionstring host library — reading text: whole files, lines and numbers, with precise errors.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "io/clip.hpp"

namespace actionstring {
namespace host {

/// Walks a text buffer line by line (LF, CRLF or lone CR endings, any bytes)
/// and raises ReadError with the file name and current line number.
class LineScanner {
public:
    /// `text` must outlive the scanner.
    LineScanner(std::string name, std::string_view text) : name_(std::move(name)), text_(text) {}

    /// Next line without its ending; false at the end of the text.
    bool next(std::string_view& line);
    /// Next line that is not blank (and, if `comment` is set, does not start with it after spaces).
    bool next_content(std::string_view& line, char comment = '\0');
    /// Steps back one line, so next() returns the same line again.
    void unread();
    std::size_t line_number() const noexcept { return line_; }
    const std::string& name() const noexcept { return name_; }
    [[noreturn]] void fail(const std::string& what) const;
    [[noreturn]] void fail_at(std::size_t line, const std::string& what) const;

private:
    std::string name_;
    std::string_view text_;
    std::size_t position_ = 0;
    std::size_t previous_position_ = 0;
    std::size_t line_ = 0;
};

/// Largest file read_file() accepts by default (256 MiB): no motion file,
/// clip list or model comes near it, and a larger one is a wrong path.
constexpr std::uint64_t default_max_file_bytes = 256ull << 20;

/// Reads a whole regular file, exactly: a directory, a file over `max_bytes`,
/// one that cannot be opened (with the system's reason) or read in full is
/// refused with a ReadError. Memory used: the file's size, once.
std::string read_file(const std::string& path, std::uint64_t max_bytes = default_max_file_bytes);

/// Writes `text` to a file, replacing it. Throws ReadError (naming the file)
/// when it cannot be opened or written.
void write_file(const std::string& path, const std::string& text);

/// Whitespace-separated tokens of a line (spaces, tabs, stray CR).
std::vector<std::string_view> split_words(std::string_view line);
/// Splits on one delimiter character, trimming spaces around each field.
std::vector<std::string_view> split_fields(std::string_view line, char delimiter);
std::string_view trim(std::string_view text);
bool iequals(std::string_view a, std::string_view b);
/// Token quoted for an error message, shortened and with control bytes escaped.
std::string quoted(std::string_view token);

/// Largest magnitude accepted for any number in a motion file: beyond it a
/// value is corrupt (angles of a few turns and coordinates of kilometres
/// stay far below).
constexpr double max_abs_value = 1.0e7;

/// Parses a whole token as a finite number within ±max_abs_value, or fails
/// with "expected <what>, got '<token>'".
double parse_number(const LineScanner& scanner, std::string_view token, const char* what);
/// Parses a whole token as a non-negative integer ≤ 2^31 − 1.
long parse_index(const LineScanner& scanner, std::string_view token, const char* what);
/// True when the token is a number (no error).
bool is_number(std::string_view token);

}  // namespace host
}  // namespace actionstring
