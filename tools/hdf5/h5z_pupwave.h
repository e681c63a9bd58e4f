/* Pupwave HDF5 filter: identifier and cd_values layout (docs/hdf5.md). C header, usable from C
 * programs that set the filter with H5Pset_filter. */
#ifndef PUPWAVE_H5Z_PUPWAVE_H
#define PUPWAVE_H5Z_PUPWAVE_H

/* From HDF5's testing range 256-511: request a registered id from The HDF Group before a release. */
#define H5Z_FILTER_PUPWAVE 402

/* cd_values[0]: mode. */
#define H5Z_PUPWAVE_MODE_MAX_ERROR 1u /* every value within bound (absolute) of the original */
#define H5Z_PUPWAVE_MODE_BPV 2u       /* bound = bits per value of each chunk */
#define H5Z_PUPWAVE_MODE_LOSSLESS 3u  /* 8- and 16-bit integers, bit exact */

/* cd_values[1], cd_values[2]: the bound as an IEEE double, low and high 32-bit words. The user
 * sets cd_values[0..2]; set_local fills the rest from the dataset: */
#define H5Z_PUPWAVE_CD_TYPE 3 /* element type: 1 u8, 2 i8, 3 u16, 4 i16, 5 f32, 6 f64 */
#define H5Z_PUPWAVE_CD_RANK 4 /* chunk dimensions kept (those larger than 1), 1..3 */
#define H5Z_PUPWAVE_CD_DIMS 5 /* that many chunk dimensions, C order (slowest first) */
#define H5Z_PUPWAVE_CD_USER 3 /* values the user gives */
#define H5Z_PUPWAVE_CD_MAX 8  /* values after set_local */

#endif
