"""Run an element-wise derivation over a large table in cache-sized blocks, on a few threads.

Why blocks: ``derive`` makes a few hundred temporary arrays. Over 250,000 rows each is
2 MB, larger than a core's L2 cache and above the C allocator's default mmap threshold,
so every temporary costs fresh pages (page faults) and a trip to main memory. In blocks of
``CHUNK_ROWS`` rows (64 KiB an array) the temporaries are reused from the heap and stay in
cache: measured about 2× faster on one core (``benchmarks/derive_speed.py``).

Why one allocation for the float outputs: the outputs are fresh memory (about 320 MB of
float columns for 1,000,000 rows of ``derive``), and the first touch of every 4 KiB page
costs the kernel a page fault (about 3 µs on the 2-core benchmark machine): 0.2 s per
million rows, as much as the arithmetic. The float columns are therefore rows of one 2-D
array; numpy asks the kernel for transparent huge pages on allocations that large, so a
fault maps 2 MiB instead of 4 KiB (measured about 6× less time). Each column is still an
ordinary contiguous, writeable float array (a row view of that 2-D array); the memory is
returned when the last of them is dropped.

Why a compute may write into the table itself (``writes_into``): ``derive`` with
uncertainties gives 162 columns a row (53 without), 10 MB a block. Computed into
temporaries and copied into the table at the block's end, they were read back after the
block's other work had pushed them out of cache: the copy took 0.58 plain-derive units
of CPU against 0.17 without uncertainties (250,000 rows, 27 Nov 2026). Written into the
table's rows as they are computed (the uncertainties, intervals and probabilities) or
right after (the plain columns, while still in cache), nothing is copied at the block's
end: 0.3–0.5 plain-derive units less, A/B in one process on 240,000 rows. Stacking
results into 2-D arrays to save numpy calls was slower: 31 quantities of a block are
2 MB an array, beyond a core's L2 cache, where one 64 KiB array at a time stays in it.

Threads are available but not the default: numpy's ufuncs release the GIL while they
loop, but a 64 KiB block's loops are so short that handing the GIL back and forth costs
more than a second core gives. On the 2-core benchmark machine, idle, 1,000,000 rows took
0.38–0.43 s on one thread and 0.45–0.62 s on two (``benchmarks/derive_speed.py --threads``,
alternating runs). ``threads=None`` therefore means ``DEFAULT_THREADS`` (1, the calling
thread); ``threads=n`` uses a pool of n, at most the cores available. Small tables (one
block) never start a thread.

The computation must be element-wise (row i of the result depends on row i of the inputs
only), so a block's rows are exactly what one pass over the whole table would give.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from functools import cache

import numpy as np

Arrays = dict[str, np.ndarray]

#: Rows per block: 8192 × 8 B = 64 KiB an array (below glibc's 128 KiB mmap threshold).
CHUNK_ROWS = 8192
#: Threads used when none are asked for (see the module docstring for the measurement).
DEFAULT_THREADS = 1


def available_cores() -> int:
    """Cores this process may run on: the most threads a pool is given."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def run_in_chunks(
    compute: Callable[..., Arrays],
    inputs: Arrays,
    threads: int | None = None,
    block_rows: int = CHUNK_ROWS,
    *,
    writes_into: bool = False,
) -> Arrays:
    """``compute(inputs)``, evaluated block by block into full-size output arrays.

    ``inputs`` are arrays of one shape (broadcast already); the outputs have that shape
    and the dtypes ``compute`` gives. ``threads`` None: ``DEFAULT_THREADS``.

    ``writes_into``: ``compute`` also takes ``into``, the outputs' rows of the block (by
    column name; None for a table of one block and for the first block, whose result
    decides the outputs), and may write a column there itself: a column it returns as
    that very array is in place already, every other one is copied (see the module
    docstring for why).
    """
    shape = next(iter(inputs.values())).shape
    rows = int(np.prod(shape))
    if rows <= block_rows:
        return compute(inputs)
    flat = {name: values.reshape(-1) for name, values in inputs.items()}

    def block(start: int, into: Arrays | None = None) -> Arrays:
        part = {name: values[start : start + block_rows] for name, values in flat.items()}
        return compute(part, into=into) if writes_into and into is not None else compute(part)

    _keep_freed_heap()
    first = block(0)
    out = _allocate(first, rows)

    def store(result: Arrays, into: Arrays) -> None:
        for name, values in result.items():
            if values is not into[name]:  # not written in place by ``compute``
                into[name][...] = values

    def work(start: int) -> None:
        into = {name: values[start : start + block_rows] for name, values in out.items()}
        store(block(start, into), into)

    store(first, {name: values[:block_rows] for name, values in out.items()})
    starts = range(block_rows, rows, block_rows)
    asked = DEFAULT_THREADS if threads is None else max(1, threads)
    workers = min(asked, available_cores(), len(starts))
    if workers > 1:
        with ThreadPoolExecutor(max_workers=workers) as pool:
            try:
                for _ in pool.map(work, starts):
                    pass  # re-raises the first failing block's exception, in row order
            except BaseException:
                pool.shutdown(cancel_futures=True)  # no point computing the rest
                raise
    else:
        for start in starts:
            work(start)
    return {name: values.reshape(shape) for name, values in out.items()}


#: Bytes of the one array ``_keep_freed_heap`` allocates and frees (see there).
HEAP_HINT_BYTES = 16 << 20


@cache
def _keep_freed_heap() -> None:
    """Let the C allocator keep the blocks' freed memory for the next block.

    glibc's malloc returns the free top of its heap to the kernel when it exceeds a trim
    threshold that it sets to twice the largest mapped block freed so far (``mallopt``'s
    dynamic threshold). A caller whose largest freed array was 2 MB (250,000 rows)
    leaves it at 4 MB, below one block's temporaries with uncertainties (about 13 MB): every
    block then faults its pages in afresh, 98,000 page faults and 0.4 s of system time per
    250,000 rows measured. Allocating and freeing one array of ``HEAP_HINT_BYTES``
    (mapped, never touched: no page is faulted in) raises the threshold to twice that,
    by the allocator's own rule: 3,700 faults. Other allocators ignore it. Once per process
    (cached): the threshold never falls again, and a one-block input never comes here."""
    hint = np.empty(HEAP_HINT_BYTES // 8)
    del hint


def _allocate(first: Arrays, rows: int) -> Arrays:
    """Empty outputs of ``rows`` rows with the dtypes of ``first``; the float64 columns are
    rows of one 2-D array (see the module docstring for why)."""
    dtypes = {name: np.asarray(values).dtype for name, values in first.items()}
    floats = [name for name, dtype in dtypes.items() if dtype == np.float64]
    shared = np.empty((len(floats), rows))
    out = {name: shared[i] for i, name in enumerate(floats)}
    for name, dtype in dtypes.items():
        if name not in out:
            out[name] = np.empty(rows, dtype=dtype)
    return {name: out[name] for name in first}  # the order compute gives
