# Sanitizer and fuzzing builds (docs/fuzzing.md).
#   PUPWAVE_SANITIZE:      everything built with ASan + UBSan (the CI's build-asan, gcc or clang).
#   PUPWAVE_BUILD_FUZZERS: clang only; the same sanitizers plus libFuzzer coverage on every
#                          object, FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION defined (chunk CRCs
#                          are not checked, so mutations reach the parsers), fuzz_* targets.
if(PUPWAVE_SANITIZE OR PUPWAVE_BUILD_FUZZERS)
  set(PUPWAVE_SANITIZER_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=undefined
                              -fno-omit-frame-pointer)
  add_compile_options(${PUPWAVE_SANITIZER_FLAGS})
  add_link_options(${PUPWAVE_SANITIZER_FLAGS})
endif()
if(PUPWAVE_BUILD_FUZZERS)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "PUPWAVE_BUILD_FUZZERS needs clang: -DCMAKE_CXX_COMPILER=clang++")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
  add_compile_definitions(FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION)
endif()
