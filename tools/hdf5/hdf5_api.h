#pragma once
// The few HDF5 functions the filter's can_apply/set_local callbacks and error reports need,
// looked up at run time in whichever libhdf5 the host process has loaded (serial or OpenMPI,
// Debian's libhdf5_serial.so.103 or libhdf5_openmpi.so.103). The plugin links no HDF5, so one
// build serves both flavours and never loads a second HDF5 next to the host's.

#include <hdf5.h>

#include <string>

namespace pupwave::h5 {

struct Hdf5Api {
  decltype(&H5Tget_class) Tget_class;
  decltype(&H5Tget_size) Tget_size;
  decltype(&H5Tget_sign) Tget_sign;
  decltype(&H5Tget_order) Tget_order;
  decltype(&H5Pget_chunk) Pget_chunk;
  decltype(&H5Pget_filter_by_id2) Pget_filter_by_id2;
  decltype(&H5Pmodify_filter) Pmodify_filter;
  decltype(&H5Epush2) Epush2;
  decltype(&H5allocate_memory) allocate_memory;
  decltype(&H5free_memory) free_memory;
  const hid_t* ERR_CLS;  // H5E_ERR_CLS_g and the error codes below (globals of the library)
  const hid_t* PLINE;
  const hid_t* CANAPPLY;
  const hid_t* SETLOCAL;
  const hid_t* CANTFILTER;
};

// The host's HDF5, or null when no HDF5 library is loaded in this process (or lacks a symbol).
const Hdf5Api* hdf5_api();

// Pushes "pupwave filter: message" on HDF5's error stack (major: data filters) when HDF5 is found.
void push_error(const Hdf5Api* api, const hid_t* minor, const char* function, const std::string& message);

}  // namespace pupwave::h5
