"""pytest configuration shared by tests/ and the doctests in erdesign/.

The fits in the test suite solve many small linear-algebra problems; a multithreaded BLAS spends more time
starting threads than computing them (about 40 times slower on a busy 2-core machine), so the tests pin BLAS to one
thread.  This must happen before numpy is first imported, hence here, at the root.
"""

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")
