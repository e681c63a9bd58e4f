"""A separate (serial) process: reads what mpi_write.py wrote and checks the bound on every value."""
import sys

import h5py
import numpy as np

source, target, bound = sys.argv[1], sys.argv[2], float(sys.argv[3])
data = np.fromfile(source, dtype="<f4").reshape(91, 91, 91)
with h5py.File(target, "r") as f:
    d = f["wmag"]
    assert not h5py.get_config().mpi
    assert list(d.id.get_create_plist().get_filter(0)[:1]) == [402], "dataset is not Pupwave-filtered"
    back = d[...]
    stored = d.id.get_storage_size()
err = float(np.abs(back.astype(np.float64) - data).max())
print(f"max error {err:.6g} (bound {bound:.6g}), ratio {data.nbytes / stored:.2f}")
sys.exit(0 if err <= bound and stored < data.nbytes / 5 else 1)
