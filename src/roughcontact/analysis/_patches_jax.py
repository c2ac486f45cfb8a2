"""Counting contact patches of a JAX mask as one compiled program (no host decision).

The array-API count of :func:`.contact_geometry._count_components` asks the host whether
a round changed anything; here the rounds are a ``lax.while_loop`` and the count stays a
device scalar, which a path fetches with the state's other numbers. Min-label
propagation: every site of the map takes the smallest label of itself and its four
neighbours in the map, the old root of each label is hooked to the new one (a scatter
minimum) and pointer jumping ``L <- L[L]`` shortens the chains (Shiloach & Vishkin,
J. Algorithms 3, 57 (1982)). Labels only decrease and always name a site of the same
patch; when a round changes nothing they are equal across every bond, so each patch has
one root ``L[i] = i``, and the roots are counted. jax is imported only by JAX callers.
"""

from __future__ import annotations

from functools import partial

import jax
import jax.numpy as jnp
from jax import lax

__all__ = ["count_patches_jax"]


@partial(jax.jit, static_argnames=("periodic",))
def count_patches_jax(mask, periodic):
    """The number of 4-connected patches of the 2D bool ``mask`` (0-d int32, on its device);
    ``periodic``: patches that touch across the boundaries are one."""
    m = mask.astype(bool)
    nx, ny = m.shape
    n = nx * ny
    site = jnp.reshape(jnp.arange(n, dtype=jnp.int32), (nx, ny))
    outside = jnp.int32(n)

    def neighbours(labels):
        out = labels
        for axis, size in ((0, nx), (1, ny)):
            index = jnp.arange(size)
            for shift in (1, -1):
                near, near_m = jnp.roll(labels, shift, axis), jnp.roll(m, shift, axis)
                bond = m & near_m
                if not periodic:  # no bond across the boundary the roll wrapped
                    edge = index == (0 if shift == 1 else size - 1)
                    bond = bond & ~(edge[:, None] if axis == 0 else edge[None, :])
                out = jnp.minimum(out, jnp.where(bond, near, outside))
        return out

    def body(c):
        labels, _ = c
        new = neighbours(labels)
        fnew, fold = jnp.reshape(new, (-1,)), jnp.reshape(labels, (-1,))
        # hook each old root to the smallest new label, scattered only from the sites whose
        # label fell (elsewhere the minimum changes nothing, as labels never exceed their
        # site): on a GPU a scatter from every site is atomics contending for one address
        # (every site outside the map names ``outside``)
        hook = jnp.where(fnew < fold, fold, n + 1)  # out of bounds: dropped
        flat = jnp.concatenate([fnew, outside[None]])
        flat = flat.at[hook].min(fnew, mode="drop")
        flat = flat[flat]
        flat = flat[flat]
        new = jnp.where(m, jnp.reshape(flat[:n], (nx, ny)), outside)
        return new, jnp.any(new != labels)

    labels = jnp.where(m, site, outside)
    labels, _ = lax.while_loop(lambda c: c[1], body, (labels, jnp.asarray(True)))
    return jnp.sum(m & (labels == site), dtype=jnp.int32)
