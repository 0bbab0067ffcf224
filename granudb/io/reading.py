"""Reading a file once: hashed as it is read, ahead of its consumer, in Arrow's memory
pool that gives memory back (used by the collision import, ``granudb.io.collision_chunks``).
"""

from __future__ import annotations

import hashlib
import queue
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from granudb.errors import ValidationError
from granudb.lazy import pyarrow as pa

#: Arrow's own setting of jemalloc's dirty-page decay, restored after an import.
JEMALLOC_DEFAULT_DECAY_MS = 1000


class HashingFile:
    """A binary file whose sha256 is updated with every byte read from it."""

    def __init__(self, path: Path) -> None:
        self._handle = Path(path).open("rb")  # noqa: SIM115 - closed by close(), its owner
        self._digest = hashlib.sha256()
        self.closed = False

    def read(self, size: int = -1) -> bytes:
        data = self._handle.read(size)
        self._digest.update(data)
        return data

    def readable(self) -> bool:
        return True

    def seekable(self) -> bool:
        return False

    def close(self) -> None:
        self._handle.close()
        self.closed = True

    def hexdigest(self) -> str:
        """The whole file's sha256 (reads what the parser has not read yet)."""
        if not self._handle.closed:
            while chunk := self._handle.read(1 << 20):
                self._digest.update(chunk)
        return self._digest.hexdigest()


@contextmanager
def arrow_memory() -> Iterator[None]:
    """Arrow's jemalloc pool for the import, where this pyarrow has it.

    The default (mimalloc) keeps what the import frees resident: the same million-row
    import peaked about 130 MB higher (530 MB against 400 MB, measured by
    benchmarks/import_speed.py). Arrays made here stay valid after the default is
    restored (each keeps its pool).
    """
    previous = pa.default_memory_pool()
    try:
        pa.set_memory_pool(pa.jemalloc_memory_pool())
        pa.jemalloc_set_decay_ms(0)  # give freed pages back at once (Arrow's default: 1 s)
    except (NotImplementedError, pa.ArrowNotImplementedError):
        yield
        return
    try:
        yield
    finally:
        pa.jemalloc_set_decay_ms(JEMALLOC_DEFAULT_DECAY_MS)
        pa.set_memory_pool(previous)


class Prefetched:
    """Iterate ``iterator`` on a thread, one item ahead of the consumer.

    The import reads and checks block k+1 (Arrow and numpy, which release the GIL) while
    block k is written (SQLite's ``executemany`` releases it inside each step): about a
    quarter less time on two cores, for one more block in memory. Items and the
    reader's exception arrive in order, so refusals are the ones a sequential read gives.
    The thread never touches the database.
    """

    _END = object()

    def __init__(self, iterator: Iterator[Any]) -> None:
        self._queue: queue.Queue[tuple[Any, BaseException | None]] = queue.Queue(maxsize=1)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, args=(iterator,), daemon=True)
        self._thread.start()

    def _put(self, item: Any, error: BaseException | None = None) -> bool:
        while not self._stop.is_set():
            try:
                self._queue.put((item, error), timeout=0.05)
                return True
            except queue.Full:
                continue
        return False

    def _run(self, iterator: Iterator[Any]) -> None:
        try:
            for item in iterator:
                if not self._put(item):
                    return
        except BaseException as exc:  # noqa: BLE001 - handed to the consumer, in order
            self._put(self._END, exc)
            return
        self._put(self._END)

    def __iter__(self) -> Iterator[Any]:
        try:
            while True:
                item, error = self._queue.get()
                if error is not None:
                    raise error
                if item is self._END:
                    return
                yield item
        finally:
            self.close()

    def close(self) -> None:
        """Stop reading ahead and wait for the thread (it finishes its current block)."""
        self._stop.set()
        self._thread.join()


#: The largest small table read whole (fluid points, a seed file): far above any real one.
MAX_SMALL_TABLE_BYTES = 16 * 1024 * 1024


def read_text_file(
    path: Path, field: str = "FILE", *, max_bytes: int = MAX_SMALL_TABLE_BYTES
) -> str:
    """The text of the small file ``path`` (UTF-8, a byte-order mark dropped), refused in
    one line when it is larger than ``max_bytes``, holds a NUL byte (a binary file: an
    image, a spreadsheet's .xlsx, an executable) or is not UTF-8."""
    with path.open("rb") as handle:
        data = handle.read(max_bytes + 1)
    return decoded_text(data, path.name, field, max_bytes=max_bytes)


def decoded_text(data: bytes, name: str, field: str = "FILE", *, max_bytes: int) -> str:
    """``data`` (the bytes of the file ``name``) as text, by ``read_text_file``'s rules."""
    if len(data) > max_bytes:
        raise ValidationError(field, name, f"is larger than {max_bytes:,} bytes")
    if b"\x00" in data:
        raise ValidationError(
            field, name, "is not a text file (it holds NUL bytes): give a CSV file"
        )
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ValidationError(
            field,
            name,
            f"is not UTF-8 text (byte {exc.start + 1} cannot be read): a binary "
            "file, or text in another encoding (save it as CSV UTF-8)",
        ) from None
