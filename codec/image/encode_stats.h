#pragma once
// Statistics of image encodes, for the callers that ask for them (prior training): one object
// passed with the options (EncodeOptions::stats). Without one no encode keeps any, so encodes on
// different threads never share state.

#include "codec/entropy/block_tally.h"

namespace pupwave {

// Every figure adds up over the encodes the object is passed to (a fresh object: one encode's).
// The tally it points to may serve several encodes at once.
struct EncodeStats {
  // Where the bit-plane coder adds each block's first bits per context (prior training,
  // block_tally.h); null: not kept (it costs a lock and map updates per block).
  ContextTally* tally = nullptr;
};

// The tally the block coder adds to under `stats` (null when none is kept).
inline ContextTally* context_tally(const EncodeStats* stats) {
  return stats != nullptr ? stats->tally : nullptr;
}

}  // namespace pupwave
