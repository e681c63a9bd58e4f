"""The HDF5 filter plugin shipped in the pip-installed package (pupwave/hdf5_plugin/): `import
pupwave` registers its folder with h5py, so h5py writes and reads filter 402 with no
HDF5_PLUGIN_PATH, in either import order."""

import os

import numpy as np
import pytest

from conftest import TESTIMAGES, run_python

h5py = pytest.importorskip("h5py")

MAX_ERROR = 0.01  # in wmag91's units


def test_h5py_writes_and_reads_the_filter_with_no_plugin_path(installed, tmp_path):
    path = tmp_path / "w.h5"
    run_python("import sys, numpy as np\n"
               "import h5py, pupwave\n"  # h5py first: the plugin folder is appended to a loaded HDF5
               "data = np.fromfile(sys.argv[1], '<f4').reshape(91, 91, 91)\n"
               "with h5py.File(sys.argv[2], 'w') as f:\n"
               "    d = f.create_dataset('x', data=data, chunks=(48, 48, 48), compression=pupwave.hdf5.FILTER_ID,\n"
               "                         compression_opts=pupwave.hdf5.filter_cd_values(max_error=float(sys.argv[3])))\n"
               "    assert d.id.get_create_plist().get_filter(0)[0] == 402",
               TESTIMAGES / "wmag91.float", path, MAX_ERROR)
    run_python("import sys, numpy as np\n"
               "import pupwave, h5py\n"
               "with h5py.File(sys.argv[1], 'r') as f:\n"
               "    np.save(sys.argv[2], f['x'][...])", path, tmp_path / "back.npy")
    data = np.fromfile(TESTIMAGES / "wmag91.float", "<f4").reshape(91, 91, 91)
    back = np.load(tmp_path / "back.npy")
    assert np.abs(back.astype(np.float64) - data).max() <= MAX_ERROR
    assert os.path.getsize(path) < data.nbytes / 2


def test_the_plugin_folder_is_the_packages_and_registered_once(installed):
    import pupwave

    folder = pupwave.hdf5.register_plugin()
    assert folder == os.path.join(os.path.dirname(pupwave.__file__), "hdf5_plugin")
    assert os.path.isfile(os.path.join(folder, pupwave.hdf5.PLUGIN_NAME))
    assert pupwave.hdf5.register_plugin() == folder
    paths = [h5py.h5pl.get(i) for i in range(h5py.h5pl.size())]
    assert paths.count(os.fsencode(folder)) == 1
