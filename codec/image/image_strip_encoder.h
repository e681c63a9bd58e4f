#pragma once
// Strip-wise forward transform for the image encoder (the counterpart of image_strips.h): a
// component's rows are read a strip at a time, each level transforms its rows as they arrive
// and its columns over windows reaching the analysis reach beyond the rows it produces
// (windowed lifting gives the whole column's coefficients bit for bit there), and every
// code-block is handed on as soon as its rows are complete, so the component is never whole
// in memory. Coefficients are identical to transform_component's.

#include <cstdint>
#include <functional>
#include <span>

#include "codec/image/image_plan.h"

namespace pupwave {

// Called with a code-block's index in plan.blocks and its coefficients (x fastest), from
// several threads at once (the blocks of a strip run as tasks of the plan's executor).
template <class T>
using BlockSink = std::function<void(std::size_t block, std::span<const T> values)>;

// Transforms component c of the plan's source by strips and hands every one of its blocks to
// `sink`; stops early (blocks left out) once `stop` returns true (asked between strips). T is
// float (irreversible plans) or int32_t (reversible). Needs plan.strip_reach > 0.
template <class T>
void stream_component(
    const ImagePlan& plan, std::size_t c, const BlockSink<T>& sink,
    const std::function<bool()>& stop = [] { return false; });

}  // namespace pupwave
