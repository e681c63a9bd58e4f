#pragma once
// Statistics of image encodes, for the callers that ask for them (prior training, tests and
// benchmarks of the coders' searches): one object passed with the options
// (EncodeOptions::stats). Without one no encode keeps any, so encodes on different threads
// never share state. Next to image_codec.h because it gathers figures from every layer an image
// encode goes through: the bit-plane block coder's context bits and the pc coder's rate search.

#include "codec/entropy/block_tally.h"

namespace pupwave {

// Every figure adds up over the encodes the object is passed to (a fresh object: one encode's).
// An object takes one encode at a time; the tally it points to may serve several at once.
struct EncodeStats {
  // Where the bit-plane coder adds each block's first bits per context (prior training,
  // block_tally.h); null: not kept (it costs a lock and map updates per block).
  ContextTally* tally = nullptr;
  // The pc coder's rate search (image_encoder_pc.h): whole coding passes, trims (codings of a
  // few finest bands, about a quarter of a pass each), and the samples coded by passes abandoned
  // before their end (not counted in pc_passes), in whole passes.
  int pc_passes = 0;
  int pc_trims = 0;
  double pc_abandoned_share = 0.0;
};

// The tally the block coder adds to under `stats` (null when none is kept).
inline ContextTally* context_tally(const EncodeStats* stats) {
  return stats != nullptr ? stats->tally : nullptr;
}

}  // namespace pupwave
