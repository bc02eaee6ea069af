// actionstring host library — pictures of an evaluation (SVG) and a Markdown summary.
#pragma once

#include <string>
#include <vector>

#include "eval/clip_eval.hpp"
#include "eval/online.hpp"

namespace actionstring {
namespace host {

/// The colour of a label (a FrameLabel) in every picture: a palette by
/// index, light grey for unknown / no action, black for a label the model lacks.
std::string label_colour(int label);

/// The confusion matrix as SVG: rows true, columns predicted (last: unknown),
/// shaded by the share of the row.
std::string confusion_svg(const ClipResults& results);

/// One stream's labels over time as SVG, like the paper's Fig. 7: the truth,
/// then the settled, live and latest-window labels, one colour per label.
std::string timeline_svg(const StreamTimeline& stream, const std::vector<std::string>& labels);

/// Writes confusion.svg, timeline_N.svg and view_N.html (one of each per
/// stream; viewer.hpp) and report.md linking
/// them into `dir` (created if missing). The first clip result is the model's.
void write_report(const std::string& dir, const std::string& title, const std::vector<ClipResults>& clip_results,
                  const OnlineReport* online, const std::vector<std::string>& labels);

}  // namespace host
}  // namespace actionstring
