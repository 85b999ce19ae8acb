"""Explicit vector loops for the backward sweep of the AFT on the contact plane (private).

The sweep (:func:`microslip.frequency._aft_plane._sweep`) updates, per slipping sample and
element, six coefficient rows of ``nbp`` values (16 at H = 7) and the two rows of its state. Written as
a plain loop, the compiler vectorises it only behind run-time checks that the nine rows do not overlap
(28 pairwise comparisons), which cost more than the 16 values they guard. The rows never overlap (they
are distinct rows of arrays the kernel allocates), so the loop is written here directly in LLVM's
vector form, ``LANES`` values at a time, without those checks. On a machine without vectors that wide
LLVM splits each operation into narrower ones: the results are the same everywhere.
"""

from __future__ import annotations

from llvmlite import ir
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

#: values per vector operation; the rows' length must be a multiple of it
LANES = 8

_DOUBLE = ir.DoubleType()
_VECTOR = ir.VectorType(_DOUBLE, LANES)


def _splat(builder, x):
    """The scalar ``x`` in every lane."""
    v = builder.insert_element(ir.Constant(_VECTOR, ir.Undefined), x, ir.Constant(ir.IntType(32), 0))
    return builder.shuffle_vector(v, ir.Constant(_VECTOR, ir.Undefined),
                                  ir.Constant(ir.VectorType(ir.IntType(32), LANES), [0] * LANES))


@intrinsic
def slip_rows(typingctx, U, m, B, Y, i, PT, coefs):  # pragma: no cover - compiled
    """Sample ``m`` of element ``i`` in the sweep, a slip, over the ``nbp`` columns (a multiple of ``LANES``).

    ``U`` (Ns, 6, nbp), ``B`` (J, nbp), ``Y`` (J, 2, nbp), ``PT`` (Ns, nbp), all C-contiguous float64
    (``beta = B[i]``, ``y = Y[i]``);
    ``coefs`` = ``(g11, g12, g13, g22, g23, h1, h2, h3, al, -al kt, v1, v2, al w.v)``. With
    ``g21 = g12``::

        U[m, 3a + b] += beta g_ab + y_a h_b     (a = 0, 1; b = 0, 1, 2)
        y_a = (al beta - al kt PT[m]) v_a + (al w.v) y_a
        beta = 0
    """
    sig = types.void(U, m, B, Y, i, PT, coefs)

    def codegen(context, builder, signature, args):
        Uv, mv, bv, yv, iv, pv, cv = args
        Ua = context.make_array(signature.args[0])(context, builder, Uv)
        ba = context.make_array(signature.args[2])(context, builder, bv)
        ya = context.make_array(signature.args[3])(context, builder, yv)
        pa = context.make_array(signature.args[5])(context, builder, pv)
        shape = cgutils.unpack_tuple(builder, Ua.shape, 3)
        nbp = shape[2]
        index = nbp.type
        base = builder.mul(mv, builder.mul(shape[1], nbp))
        urows = [builder.gep(Ua.data, [builder.add(base, builder.mul(ir.Constant(index, r), nbp))]) for r in range(6)]
        brow = builder.gep(ba.data, [builder.mul(iv, nbp)])
        y1 = builder.gep(ya.data, [builder.mul(iv, builder.add(nbp, nbp))])
        y2 = builder.gep(y1, [nbp])
        prow = builder.gep(pa.data, [builder.mul(mv, nbp)])
        g11, g12, g13, g22, g23, h1, h2, h3, al, malkt, v1, v2, awv = (
            _splat(builder, builder.extract_value(cv, j)) for j in range(13))
        g = (g11, g12, g13, g12, g22, g23)
        h = (h1, h2, h3, h1, h2, h3)
        fma_fn = cgutils.get_or_insert_function(builder.module, ir.FunctionType(_VECTOR, [_VECTOR] * 3),
                                                "llvm.fma.v%df64" % LANES)

        def fma(a, b, c):
            return builder.call(fma_fn, [a, b, c])

        entry = builder.block
        loop = builder.append_basic_block("slip_rows.loop")
        done = builder.append_basic_block("slip_rows.done")
        builder.cbranch(builder.icmp_signed(">", nbp, ir.Constant(index, 0)), loop, done)
        builder.position_at_end(loop)
        p = builder.phi(index)
        p.add_incoming(ir.Constant(index, 0), entry)

        def at(ptr):
            return builder.bitcast(builder.gep(ptr, [p]), _VECTOR.as_pointer())

        bp = builder.load(at(brow), align=8)
        a1 = builder.load(at(y1), align=8)
        a2 = builder.load(at(y2), align=8)
        pt = builder.load(at(prow), align=8)
        for r in range(6):
            ptr = at(urows[r])
            builder.store(fma(bp, g[r], fma(a1 if r < 3 else a2, h[r], builder.load(ptr, align=8))), ptr, align=8)
        q = fma(pt, malkt, builder.fmul(al, bp))
        builder.store(fma(q, v1, builder.fmul(awv, a1)), at(y1), align=8)
        builder.store(fma(q, v2, builder.fmul(awv, a2)), at(y2), align=8)
        builder.store(ir.Constant(_VECTOR, [0.0] * LANES), at(brow), align=8)
        following = builder.add(p, ir.Constant(index, LANES))
        p.add_incoming(following, builder.block)
        builder.cbranch(builder.icmp_signed("<", following, nbp), loop, done)
        builder.position_at_end(done)
        return context.get_dummy_value()

    return sig, codegen
