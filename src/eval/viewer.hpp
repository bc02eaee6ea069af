// actionstring host library — a page to look at one stream: the skeleton
// playing, the true and predicted label timelines under it, the confidence.
#pragma once

#include <string>
#include <vector>

#include "eval/online.hpp"

namespace actionstring {
namespace host {

/// One self-contained HTML page (no network access, no external scripts or
/// fonts) that plays `stream`'s skeleton in 3D (drag to turn it) with a time
/// slider, and under it the label timelines as in the paper's Fig. 7: the
/// truth (when known), the settled labels, the live labels and the paper's
/// window rule, then the live label's margin (its confidence) and the action
/// events. `labels` are the model's label names.
///
/// The skeleton is stored at most 30 frames per second (fewer for long
/// streams, so a page stays a few MB), as 16-bit millimetres; the timelines
/// keep every frame. The page checks itself once drawn: the root element's
/// `data-check` attribute says how many pixels each canvas drew and
/// `data-errors` lists any script error (what the browser test reads).
std::string viewer_html(const StreamTimeline& stream, const std::vector<std::string>& labels,
                        const std::string& title);

}  // namespace host
}  // namespace actionstring
