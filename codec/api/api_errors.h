#pragma once
// Internal to codec/api: turns the codec's exceptions into the public api::Error with a Status,
// so the C++ API documents one exception type and the C API one set of codes.

#include <exception>
#include <new>
#include <stdexcept>

#include "codec/error.h"
#include "pupwave/pupwave.hpp"

namespace pupwave::api::detail {

// Calls f(); rethrows the codec's exceptions as api::Error (bad_alloc passes through).
template <class F>
auto translate_errors(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const DecodeError& e) {
    throw Error(Status::corrupt_stream, e.what());
  } catch (const EncodeError& e) {
    throw Error(Status::unsupported, e.what());
  } catch (const std::invalid_argument& e) {
    throw Error(Status::invalid_argument, e.what());
  } catch (const std::length_error& e) {
    throw Error(Status::invalid_argument, e.what());
  } catch (const std::out_of_range& e) {
    throw Error(Status::invalid_argument, e.what());
  } catch (const std::exception& e) {
    throw Error(Status::unsupported, e.what());
  }
}

[[noreturn]] inline void fail(const std::string& message) { throw Error(Status::invalid_argument, message); }

}  // namespace pupwave::api::detail
