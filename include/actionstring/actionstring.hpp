// actionstring — umbrella header: the whole allocation-free runtime.
//
// Real-time action labelling from skeleton motion after Qi et al., "Real-time
// motion data annotation via action string" (CAVW 2014).
#pragma once

#include "actionstring/version.hpp"
#include "actionstring/status.hpp"
#include "actionstring/model.hpp"
#include "actionstring/storage.hpp"
#include "actionstring/normalize.hpp"
#include "actionstring/motion.hpp"
#include "actionstring/projection.hpp"
#include "actionstring/gmm.hpp"
#include "actionstring/tree.hpp"
#include "actionstring/sampler.hpp"
#include "actionstring/encoder.hpp"
#include "actionstring/events.hpp"
#include "actionstring/string_distance.hpp"
#include "actionstring/matcher.hpp"
#include "actionstring/classify.hpp"
#include "actionstring/exemplars.hpp"
#include "actionstring/descriptor.hpp"
#include "actionstring/clip.hpp"
#include "actionstring/annotator.hpp"
#include "actionstring/blob.hpp"
