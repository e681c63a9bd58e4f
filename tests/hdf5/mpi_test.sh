#!/usr/bin/env bash
# Parallel HDF5 with the Pupwave filter: `mpirun -n 2` ranks write one filtered 3-D dataset
# collectively (mpi_write.py, h5py's MPI build), then a separate serial process reads it back and
# checks the bound on every value (mpi_check.py). Usage: mpi_test.sh PYTHON WORKDIR TESTIMAGES_DIR
set -euo pipefail
python=$1 work=$2 images=$3
here="$(cd "$(dirname "$0")" && pwd)"
mkdir -p "$work"
rm -f "$work/mpi.h5"
# Root in containers and CI needs explicit consent; single-host runs need no network discovery.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
bound=0.1  # about 1e-3 of the value range
timeout 240 mpirun -n 2 --oversubscribe "$python" "$here/mpi_write.py" "$images/wmag91.float" "$work/mpi.h5" "$bound"
"$python" "$here/mpi_check.py" "$images/wmag91.float" "$work/mpi.h5" "$bound"
