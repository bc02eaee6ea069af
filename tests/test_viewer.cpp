// The viewer page: its data is what the stream holds, it cannot be broken out
// of by a label's name, and long streams are thinned to a bounded page.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "common/paths.hpp"
#include "eval/viewer.hpp"

using namespace actionstring;
using namespace actionstring::host;

namespace {

StreamTimeline stream_of(std::size_t frames, std::size_t joints, double rate_hz) {
    StreamTimeline s;
    s.name = "test stream";
    s.joints = joints;
    for (std::size_t f = 0; f < frames; ++f) s.times_s.push_back(static_cast<double>(f) / rate_hz);
    s.positions.assign(frames * joints * 3, 0.5f);
    s.labels.settled.assign(frames, 0);
    s.labels.live.assign(frames, unknown_frame);
    s.labels.window.assign(frames, 1);
    s.labels.margin.assign(frames, 0.25f);
    return s;
}

// The value of "key": [...] or "key": "..." in the page's data.
std::string field(const std::string& page, const std::string& key) {
    const std::size_t at = page.find("\"" + key + "\":");
    REQUIRE(at != std::string::npos);
    const std::size_t begin = at + key.size() + 3;
    const char close = page[begin] == '[' ? ']' : '"';
    const std::size_t end = page.find(close, begin + 1);
    return page.substr(begin + 1, end - begin - 1);
}

std::size_t count(const std::string& text, const std::string& needle) {
    std::size_t n = 0;
    for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
    return n;
}

std::vector<std::uint8_t> unbase64(const std::string& text) {
    const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::vector<std::uint8_t> out;
    std::uint32_t bits = 0;
    int have = 0;
    for (const char c : text) {
        if (c == '=') break;
        bits = (bits << 6) | static_cast<std::uint32_t>(alphabet.find(c));
        have += 6;
        if (have >= 8) {
            have -= 8;
            out.push_back(static_cast<std::uint8_t>((bits >> have) & 0xFF));
        }
    }
    return out;
}

}  // namespace

TEST_CASE("viewer: positions in millimetres, labels and margins as streamed") {
    StreamTimeline s = stream_of(4, 2, 30.0);
    s.positions[0] = 1.2345f;    // frame 0, joint 0, x
    s.positions[4] = -0.0004f;   // joint 1, y
    s.positions[11] = 40.0f;     // beyond 16-bit millimetres: clamped
    s.positions[6] = std::numeric_limits<float>::quiet_NaN();  // frame 1: never NaN on the page
    s.labels.margin[2] = std::numeric_limits<float>::infinity();
    s.truth = {0, 0, -1, -2};
    const std::string page = viewer_html(s, {"alpha", "beta"}, "a title");
    CHECK(field(page, "times") == "0.0000,0.0333,0.0667,0.1000");
    CHECK(field(page, "margin") == "0.250,0.250,null,0.250");
    CHECK(field(page, "labels") == "\"alpha\",\"beta\"");
    CHECK(page.find("{\"name\":\"truth\",\"spans\":[[0.0000,0.0667,0],[0.0667,0.1000,-1],[0.1000,0.1000,-2]]}") !=
          std::string::npos);
    const std::vector<std::uint8_t> bytes = unbase64(field(page, "positions"));
    REQUIRE(bytes.size() == 4 * 2 * 3 * 2);
    auto mm = [&](std::size_t i) { return static_cast<std::int16_t>(bytes[2 * i] | (bytes[2 * i + 1] << 8)); };
    CHECK(mm(0) == 1235);
    CHECK(mm(1) == 500);
    CHECK(mm(4) == 0);
    CHECK(mm(11) == 32767);
    CHECK(mm(6) == 0);
    CHECK(page.find("nan") == std::string::npos);
    CHECK(page.find("inf") == std::string::npos);
}

TEST_CASE("viewer: a label's name cannot end the page's script") {
    const StreamTimeline s = stream_of(10, 1, 30.0);
    const std::string plain = viewer_html(s, {"a", "b"}, "t");
    const std::string hostile = viewer_html(s, {"</script><script>alert(1)</script>", "b"}, "</script>");
    CHECK(count(hostile, "</script>") == count(plain, "</script>"));
    CHECK(hostile.find("<\\/script><script>alert(1)<\\/script>") != std::string::npos);
}

TEST_CASE("viewer: at most 30 skeleton frames a second, fewer for long streams") {
    // 120 Hz for 10 s (0 … 9.992 s): ticks 0 … 300 of a 30 Hz grid on the page.
    const StreamTimeline s = stream_of(1200, 3, 120.0);
    const std::string page = viewer_html(s, {"a", "b"}, "t");
    CHECK(count(field(page, "times"), ",") + 1 == 301);
    CHECK(page.find("\"streamFrames\":1200") != std::string::npos);
    // 100 joints for 400 s at 30 Hz (3.6 million coordinates): thinned to at most 1.5 million.
    const StreamTimeline big = stream_of(12000, 100, 30.0);
    const std::string big_page = viewer_html(big, {"a", "b"}, "t");
    const std::size_t shown = count(field(big_page, "times"), ",") + 1;
    CHECK(shown * 300 <= 1500000);
    CHECK(shown >= 4900);
    CHECK(unbase64(field(big_page, "positions")).size() == shown * 300 * 2);
}

TEST_CASE("viewer: a stream without a skeleton still gets a page") {
    StreamTimeline s = stream_of(5, 2, 30.0);
    s.positions.clear();
    const std::string page = viewer_html(s, {"a", "b"}, "t");
    CHECK(field(page, "positions").empty());
    CHECK(page.find("\"rows\":[{\"name\":\"settled\"") != std::string::npos);  // no truth row when not known
}

TEST_CASE("pages and reports name files by their last two path components") {
    CHECK(actionstring::host::short_path("/work/shared/data/msr-action3d/test.tsv") == "msr-action3d/test.tsv");
    CHECK(actionstring::host::short_path("results/msr.model") == "results/msr.model");
    CHECK(actionstring::host::short_path("msr.model") == "msr.model");
    CHECK(actionstring::host::short_path("./msr.model") == "msr.model");
}
