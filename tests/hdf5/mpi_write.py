"""Run by `mpirun -n 2`: writes testimages/wmag91.float into one Pupwave-filtered 3-D dataset with
parallel HDF5 (h5py's MPI build), collectively, each rank its own slab of whole chunks."""
import sys

import h5py
import numpy as np
from mpi4py import MPI

from pupwave.hdf5 import hdf5_filter

source, target, bound = sys.argv[1], sys.argv[2], float(sys.argv[3])
comm = MPI.COMM_WORLD
assert h5py.get_config().mpi, "h5py is not the MPI build"
data = np.fromfile(source, dtype="<f4").reshape(91, 91, 91)
chunk = (48, 48, 48)
# Rank r owns the z-slab of chunk row r: no two ranks ever touch one chunk.
z0 = comm.rank * chunk[0]
z1 = min(data.shape[0], z0 + chunk[0])
with h5py.File(target, "w", driver="mpio", comm=comm) as f:
    d = f.create_dataset("wmag", shape=data.shape, dtype="f4", chunks=chunk, **hdf5_filter(max_error=bound))
    with d.collective:
        d[z0:z1] = data[z0:z1]
print(f"rank {comm.rank} of {comm.size} wrote z {z0}..{z1} with {h5py.version.hdf5_version} (mpi)")
