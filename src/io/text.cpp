#include "io/text.hpp"

#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <sys/stat.h>

namespace actionstring {
namespace host {

ReadError::ReadError(std::string file, std::size_t line, const std::string& what)
    : std::runtime_error(line > 0 ? file + ":" + std::to_string(line) + ": " + what : file + ": " + what),
      file_(std::move(file)),
      line_(line) {}

std::string read_file(const std::string& path, std::uint64_t max_bytes) {
    auto reason = [] { return std::string(std::strerror(errno)); };
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) throw ReadError(path, 0, "cannot open the file: " + reason());
    if (S_ISDIR(info.st_mode)) throw ReadError(path, 0, "is a directory, not a file");
    if (!S_ISREG(info.st_mode)) throw ReadError(path, 0, "is not a regular file");
    const auto size = static_cast<std::uint64_t>(info.st_size);
    if (size > max_bytes)
        throw ReadError(path, 0, "the file has " + std::to_string(size) + " bytes; files over " + std::to_string(max_bytes) +
                                     " bytes are refused (no motion file, list or model is that large)");
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (file == nullptr) throw ReadError(path, 0, "cannot open the file: " + reason());
    std::string content(static_cast<std::size_t>(size), '\0');
    const std::size_t got = size == 0 ? 0 : std::fread(content.data(), 1, content.size(), file);
    const bool failed = std::ferror(file) != 0;
    const int read_errno = errno;
    std::fclose(file);
    if (failed) throw ReadError(path, 0, "cannot read the file: " + std::string(std::strerror(read_errno)));
    if (got != content.size())
        throw ReadError(path, 0, "read " + std::to_string(got) + " of its " + std::to_string(size) +
                                     " bytes (the file changed while it was read?)");
    return content;
}

void write_file(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw ReadError(path, 0, "cannot open the file for writing");
    out << text;
    out.flush();
    if (!out) throw ReadError(path, 0, "cannot write the file");
}

bool LineScanner::next(std::string_view& line) {
    if (position_ >= text_.size()) return false;
    previous_position_ = position_;
    std::size_t end = position_;
    while (end < text_.size() && text_[end] != '\n' && text_[end] != '\r') ++end;
    line = text_.substr(position_, end - position_);
    if (end < text_.size() && text_[end] == '\r') ++end;
    if (end < text_.size() && text_[end] == '\n') ++end;
    position_ = end;
    ++line_;
    return true;
}

bool LineScanner::next_content(std::string_view& line, char comment) {
    while (next(line)) {
        const std::string_view t = trim(line);
        if (t.empty() || (comment != '\0' && t.front() == comment)) continue;
        return true;
    }
    return false;
}

void LineScanner::unread() {
    if (position_ == previous_position_) return;
    position_ = previous_position_;
    --line_;
}

void LineScanner::fail(const std::string& what) const { throw ReadError(name_, line_, what); }
void LineScanner::fail_at(std::size_t line, const std::string& what) const { throw ReadError(name_, line, what); }

namespace {
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
}  // namespace

std::vector<std::string_view> split_words(std::string_view line) {
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && is_space(line[i])) ++i;
        const std::size_t start = i;
        while (i < line.size() && !is_space(line[i])) ++i;
        if (i > start) words.push_back(line.substr(start, i - start));
    }
    return words;
}

std::string_view trim(std::string_view text) {
    while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
    while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
    return text;
}

std::vector<std::string_view> split_fields(std::string_view line, char delimiter) {
    std::vector<std::string_view> fields;
    std::size_t start = 0;
    for (;;) {
        const std::size_t end = line.find(delimiter, start);
        fields.push_back(
            trim(line.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start)));
        if (end == std::string_view::npos) break;
        start = end + 1;
    }
    return fields;
}

bool iequals(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; };
        if (lower(a[i]) != lower(b[i])) return false;
    }
    return true;
}

std::string quoted(std::string_view token) {
    std::string out = "'";
    const std::size_t shown = token.size() > 40 ? 40 : token.size();
    for (std::size_t i = 0; i < shown; ++i) {
        const auto c = static_cast<unsigned char>(token[i]);
        if (c < 0x20 || c >= 0x7F) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\x%02X", c);
            out += escaped;
        } else {
            out += static_cast<char>(c);
        }
    }
    if (shown < token.size()) out += "...";
    return out + "'";
}

namespace {
bool parse_double(std::string_view token, double& value) {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    if (token.empty()) return false;
    const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
    return result.ec == std::errc() && result.ptr == token.data() + token.size();
}
}  // namespace

bool is_number(std::string_view token) {
    double value = 0;
    return parse_double(token, value) && std::isfinite(value);
}

double parse_number(const LineScanner& scanner, std::string_view token, const char* what) {
    double value = 0;
    if (!parse_double(token, value)) scanner.fail(std::string("expected ") + what + ", got " + quoted(token));
    if (!std::isfinite(value)) scanner.fail(std::string("expected a finite ") + what + ", got " + quoted(token));
    if (std::fabs(value) > max_abs_value)
        scanner.fail(std::string(what) + " " + quoted(token) + " is out of range (|value| > 1e7)");
    return value;
}

long parse_index(const LineScanner& scanner, std::string_view token, const char* what) {
    long value = 0;
    const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
    if (result.ec != std::errc() || result.ptr != token.data() + token.size() || value < 0 || value > 2147483647L)
        scanner.fail(std::string("expected ") + what + " (a whole number ≥ 0), got " + quoted(token));
    return value;
}

}  // namespace host
}  // namespace actionstring
