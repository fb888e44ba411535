"""files.disk_full: the error a full disk raises names the file, the free space on the device
of its nearest existing directory, and keeps the errno (ENOSPC) for callers that test it."""
from __future__ import annotations

import errno

from hotroll.files import DiskFullError, disk_full


def test_a_full_disk_names_the_file_its_device_and_keeps_the_errno(tmp_path):
    path = tmp_path / "not" / "yet" / "summary.json"
    e = disk_full(path, OSError(errno.ENOSPC, "No space left on device"))
    assert isinstance(e, DiskFullError) and e.errno == errno.ENOSPC
    assert str(e).startswith(f"[Errno {errno.ENOSPC}] disk full: no space left writing {path} (")
    assert f"MB free on the device of {tmp_path});" in str(e)
