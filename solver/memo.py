"""Product memo shared by the solvers: the last converged fields of an operator and their products.

A rolling step hands the previous step's converged traction back as the memory tau' (and the normal solve
may start from the previous pressure), so the product A tau' that the previous solve already carried is
free when the field is bit-for-bit a stored one. The carried products are updated incrementally by the
solvers (u += alpha A v, exact in exact arithmetic) and drift by round-off only; after `max_reuses` reuses
an entry is not offered again, so the product is then recomputed by FFT. The entries are kept most recently used
first: a field looked up again and again (the memory tau' of every solve of a friction law's iteration within one
step) stays while the solves' own results come and go.
"""
import weakref

from rollcontact.bem.compiled import kernel


@kernel("b1(f8[::1], f8[::1])")
def _same(a, b):
    """a == b element by element (flat float64 views), stopping at the first difference."""
    for i in range(a.size):
        if a[i] != b[i]:
            return False
    return True


def same(a, b) -> bool:
    """True if the two float64 arrays have the same shape and the same values."""
    return a.shape == b.shape and _same(a.reshape(-1), b.reshape(-1))


class ProductMemo:
    """Per operator, up to `size` (field, product, reuses) entries, the most recently stored or found first."""

    def __init__(self, size=1, max_reuses=32):
        self.size = size
        self.max_reuses = max_reuses
        self._entries = weakref.WeakKeyDictionary()

    def lookup(self, op, field):
        """(product, reuses + 1) if `field` equals a stored field that may still be reused (the entry then moves to
        the front), else (None, 0)."""
        entries = self._entries.get(op, [])
        for k, (stored, product, reuses) in enumerate(entries):
            if reuses < self.max_reuses and same(stored, field):
                if k:
                    entries.insert(0, entries.pop(k))
                return product, reuses + 1
        return None, 0

    def store(self, op, field, product, reuses):
        """Keep copies of `field` and its `product` (replacing an equal stored field)."""
        older = [e for e in self._entries.get(op, ()) if not same(e[0], field)]
        self._entries[op] = [(field.copy(), product.copy(), reuses)] + older[: self.size - 1]

    def clear(self):
        self._entries.clear()
