r"""Mirror symmetry of a sensor: its dense factorization split into four independent blocks.

A square or rectangular array whose cover, taxels and load grid are symmetric under the two
mirror reflections (rows reversed, columns reversed) has an operator that commutes with
them, and so does the penalty (its DCT modes are even or odd). Every vector splits into
four parts, even or odd along each axis, and the operator maps each part of the load grid
to the same part of the readings. The SVD of the standard form then splits into four SVDs
a quarter the size, and applying its factors costs a quarter of the dense products: fold
the frames into parts (sums of mirrored quadrants), multiply four small blocks, unfold.

`fold` sums mirrored quadrants without normalizing: the part c of x is x @ G_c with
G_c^T G_c = 4 I, and `unfold` is the adjoint, so unfold(fold(x)) = 4 x.
"""

from __future__ import annotations

import numpy as np

__all__ = ["MirrorBlocks", "fold", "mirror_blocks", "unfold"]

PARTS = 4  # even-even, even-odd, odd-even, odd-odd (rows, then columns)
_BLOCK_TOLERANCE = 1e-10  # largest coupling between parts, relative to the matrix
# frames per chunk: about 1 MB of load grid, so that the temporaries are reused memory (a
# fresh multi-megabyte array costs its page faults, more than the products it holds)
_CHUNK_BYTES = 1 << 20


def fold(values: np.ndarray) -> list[np.ndarray]:
    """The four mirror parts of a batch (B, rows, cols) of even sizes, each (B, rows cols / 4).

    Examples
    --------
    >>> x = np.arange(16.0).reshape(1, 4, 4)
    >>> [float(part[0, 0]) for part in fold(x)]  # x[0, 0] and its mirror images, signed
    [30.0, -6.0, -24.0, 0.0]
    """
    batch, rows, cols = values.shape
    top, bottom = values[:, : rows // 2], values[:, ::-1][:, : rows // 2]
    parts = []
    for half in (top + bottom, top - bottom):
        left, right = half[:, :, : cols // 2], half[:, :, ::-1][:, :, : cols // 2]
        parts.append((left + right).reshape(batch, -1))
        parts.append((left - right).reshape(batch, -1))
    return parts


def unfold(
    parts: list[np.ndarray], shape: tuple[int, int], out: np.ndarray | None = None
) -> np.ndarray:
    """The adjoint of `fold`: four parts (B, rows cols / 4) back to a batch (B, rows, cols)."""
    rows, cols = shape[0] // 2, shape[1] // 2
    even_even, even_odd, odd_even, odd_odd = (p.reshape(p.shape[0], rows, cols) for p in parts)
    if out is None:
        out = np.empty((even_even.shape[0], *shape))
    even_rows, odd_rows = even_even + odd_even, even_even - odd_even
    even_cols, odd_cols = even_odd + odd_odd, even_odd - odd_odd
    np.add(even_rows, even_cols, out=out[:, :rows, :cols])
    np.subtract(even_rows, even_cols, out=out[:, :rows, ::-1][:, :, :cols])
    np.add(odd_rows, odd_cols, out=out[:, ::-1][:, :rows, :cols])
    np.subtract(odd_rows, odd_cols, out=out[:, ::-1, ::-1][:, :rows, :cols])
    return out


def _basis(shape: tuple[int, int]) -> list[np.ndarray]:
    """G_c of each part, shape (cells, cells / 4): `fold` of the identity."""
    cells = shape[0] * shape[1]
    return fold(np.eye(cells).reshape(cells, *shape))


class MirrorBlocks:
    """The SVD of a mirror-symmetric matrix, part by part, and its fast application.

    Parameters
    ----------
    readings : list of numpy.ndarray
        G_c of the readings' grid, one per part.
    cells : list of numpy.ndarray
        G_c of the load grid, one per part.
    parts : numpy.ndarray of int
        The part of each singular mode, modes grouped part by part.
    """

    def __init__(self, readings: list, cells: list, parts: np.ndarray) -> None:
        self._readings, self._cells = readings, cells
        self.parts = parts
        self._modes = [np.flatnonzero(parts == part) for part in range(PARTS)]
        self._analysis: list[np.ndarray] = []
        self._synthesis: list[np.ndarray] = []
        self._shape: tuple[int, int] = (0, 0)
        self._extra = 0  # directions analyzed and synthesized with the even-even modes

    def keep(self, kept: np.ndarray) -> None:
        """Keep only some modes (a boolean mask in mode order), as the spectrum does."""
        self.parts = self.parts[kept]
        self._modes = [np.flatnonzero(self.parts == part) for part in range(PARTS)]

    def prepare(
        self, vectors: np.ndarray, synthesis: np.ndarray, extra: np.ndarray, shape: tuple
    ) -> None:
        """Blocks for analysis (readings @ vectors) and synthesis (coefficients @ synthesis).

        `extra` are directions of the readings (columns) analyzed and synthesized along with
        the even-even modes (the image of the penalty's null space): its rows of `synthesis`
        follow the modes'.
        """
        self._shape = shape
        self._extra = extra.shape[1]
        modes = self._modes
        columns = [vectors[:, m] for m in modes]
        columns[0] = np.hstack([columns[0], extra])
        rows = [synthesis[m] for m in modes]
        rows[0] = np.vstack([rows[0], synthesis[len(self.parts) :]])
        self._analysis = [g.T @ c / 4 for g, c in zip(self._readings, columns, strict=True)]
        self._synthesis = [r @ g / 4 for g, r in zip(self._cells, rows, strict=True)]

    def _chunks(self, batch: int) -> list[slice]:
        size = max(_CHUNK_BYTES // (8 * self._shape[0] * self._shape[1]), 1)
        return [slice(start, start + size) for start in range(0, batch, size)]

    def analyze(self, frames: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Coefficients on the modes (B, r) and on the extra directions (B, extra)."""
        batch = frames.shape[0]
        coefficients = np.empty((batch, self.parts.size))
        extra = np.empty((batch, self._extra))
        first = self._modes[0].size
        for chunk in self._chunks(batch):
            folded = fold(frames[chunk])
            products = [part @ block for part, block in zip(folded, self._analysis, strict=True)]
            for modes, product in zip(self._modes, products, strict=True):
                coefficients[chunk, modes] = product[:, : modes.size]
            extra[chunk] = products[0][:, first:]  # the extra directions ride on even-even
        return coefficients, extra

    def synthesize(
        self, filtered: np.ndarray, extra: np.ndarray, out: np.ndarray | None = None
    ) -> np.ndarray:
        """Load-grid batch (B, rows, cols) from mode coefficients and extra coefficients."""
        if out is None:
            out = np.empty((filtered.shape[0], *self._shape))
        for chunk in self._chunks(filtered.shape[0]):
            groups = [filtered[chunk, modes] for modes in self._modes]
            if self._extra:
                groups[0] = np.concatenate([groups[0], extra[chunk]], axis=1)
            parts = [group @ block for group, block in zip(groups, self._synthesis, strict=True)]
            unfold(parts, self._shape, out[chunk])
        return out


def mirror_blocks(
    matrix: np.ndarray, shape: tuple[int, int], load_shape: tuple[int, int]
) -> tuple[np.ndarray, np.ndarray, np.ndarray, MirrorBlocks] | None:
    """The thin SVD of `matrix` (readings x cells) part by part, or None without the symmetry.

    Returns U, s, V^T as `numpy.linalg.svd` with ``full_matrices=False`` would, modes grouped
    by part (each part's in decreasing order), each mode lying in exactly one part.

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> half = rng.normal(size=(2, 2, 2, 2))
    >>> kernel = half + half[::-1, :, ::-1] + half[:, ::-1, :, ::-1] + half[::-1, ::-1, ::-1, ::-1]
    >>> matrix = kernel.reshape(4, 4)
    >>> u, s, vt, blocks = mirror_blocks(matrix, (2, 2), (2, 2))
    >>> bool(np.allclose(u * s @ vt, matrix))
    True
    """
    if any(size % 2 for size in (*shape, *load_shape)):
        return None
    readings, cells = _basis(shape), _basis(load_shape)
    blocks = [[g.T @ matrix @ h / 4 for h in cells] for g in readings]
    pairs = [(a, b) for a in range(PARTS) for b in range(PARTS) if a != b]
    coupling = max(np.abs(blocks[a][b]).max() for a, b in pairs)
    if coupling > _BLOCK_TOLERANCE * np.abs(matrix).max():
        return None
    us, ss, vts, parts = [], [], [], []
    for part in range(PARTS):
        u, s, vt = np.linalg.svd(blocks[part][part], full_matrices=False)
        us.append(readings[part] @ u / 2)
        ss.append(s)
        vts.append(vt @ cells[part].T / 2)
        parts.append(np.full(s.size, part))
    labels = np.concatenate(parts)
    return np.hstack(us), np.concatenate(ss), np.vstack(vts), MirrorBlocks(readings, cells, labels)
