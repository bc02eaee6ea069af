// libFuzzer entry point for one reader, chosen at compile time by
// ACTIONSTRING_FUZZ_<NAME>. Any input must end in a clip or a ReadError:
// anything else (crash, sanitizer report, hang, other exception, NaN in a
// clip) is a bug.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "io/clip_list.hpp"
#include "io/formats.hpp"

using namespace actionstring::host;

namespace {

// A small skeleton the AMC target reads its frames against.
const char* const kSkeleton =
    ":units\n  length 0.45\n  angle deg\n"
    ":root\n   order TX TY TZ RX RY RZ\n   axis XYZ\n   position 0 0 0\n   orientation 0 0 0\n"
    ":bonedata\n"
    "  begin\n     name lhipjoint\n     direction 1 0 0\n     length 2\n     axis 0 0 0 XYZ\n  end\n"
    "  begin\n     name lfemur\n     direction 0 -1 0\n     length 7\n     axis 0 0 20 XYZ\n    dof rx ry rz\n  end\n"
    "  begin\n     name rhipjoint\n     direction -1 0 0\n     length 2\n     axis 0 0 0 XYZ\n  end\n"
    ":hierarchy\n  begin\n    root lhipjoint rhipjoint\n    lhipjoint lfemur\n  end\n";

void check(const Clip& clip) {
    if (clip.positions.size() != clip.frame_count() * clip.joint_count() * 3) std::abort();
    for (float v : clip.positions)
        if (!std::isfinite(v)) std::abort();
    for (double t : clip.times)
        if (!std::isfinite(t)) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
#if defined(ACTIONSTRING_FUZZ_ASF)
        const AsfSkeleton skeleton = parse_asf("fuzz.asf", text);
        (void)skeleton;
#elif defined(ACTIONSTRING_FUZZ_AMC)
        static const AsfSkeleton skeleton = parse_asf("skeleton.asf", kSkeleton);
        check(parse_amc("fuzz.amc", text, skeleton));
#elif defined(ACTIONSTRING_FUZZ_BVH)
        check(parse_bvh("fuzz.bvh", text));
#elif defined(ACTIONSTRING_FUZZ_MSR)
        check(parse_msr_skeleton("fuzz.txt", text));
#elif defined(ACTIONSTRING_FUZZ_UTKINECT)
        check(parse_utkinect("fuzz.txt", text));
        parse_utkinect_labels("fuzz_labels.txt", text);
#elif defined(ACTIONSTRING_FUZZ_CSV)
        check(parse_joint_csv("fuzz.csv", text));
#elif defined(ACTIONSTRING_FUZZ_NTU)
        check(parse_ntu_skeleton("fuzz.skeleton", text));
#elif defined(ACTIONSTRING_FUZZ_CLIP_LIST)
        parse_clip_list("fuzz.tsv", text, "folder");
#else
#error "define one ACTIONSTRING_FUZZ_<READER>"
#endif
    } catch (const ReadError&) {
        // The expected outcome for malformed input.
    }
    return 0;
}
