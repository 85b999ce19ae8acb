"""Explicit vector loops for the AFT on the contact plane: its periods, its derivatives' passes (private).

The sweep (:func:`microslip.kernels.aft_plane._sweep`) adds, at each sample, every element's
contribution to six coefficient rows of ``nbp`` values (16 at H = 7) and updates its three state rows.
Written as plain loops, the compiler vectorises them only behind run-time checks that the rows do not
overlap (28 pairwise comparisons for one element), which cost more than the 16 values they guard. The
rows never overlap (they are distinct rows of arrays the kernel allocates), so :func:`sample_rows` is
written here directly in LLVM's vector form, ``LANES`` values at a time, without those checks, the six
sums of a sample kept in registers while the elements add to them. On a machine without vectors that
wide LLVM splits each operation into narrower ones: the results are the same everywhere.

The period (:func:`microslip.kernels.aft_plane._period`) updates every element at every sample; a
compiled loop over the elements calling :func:`microslip.kernels.element.plane_step` vectorises likewise only
behind run-time checks between its dozen rows, repeated at every sample (at J = 8 slower than one
element at a time). :func:`period_march` is that loop in vector form, without the checks, a whole period per
call, its elements' sliders held in registers from sample to sample; :func:`start_weights` runs the elements'
forward products through the periodic period the same way. :func:`project_rows` and
:func:`columns_times_basis` are the small products with the basis rows (the forces' coefficients, the
columns of the Jacobian), their sums in registers.
"""

from __future__ import annotations

from llvmlite import ir
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

from .plane_lanes import counted_loop, inverse_root, splat, stretch

#: values per vector operation; the rows' length must be a multiple of it
LANES = 16

_DOUBLE = ir.DoubleType()
_VECTOR = ir.VectorType(_DOUBLE, LANES)
#: elements per vector operation in the period's march (four: the march waits on each sample's square root and
#: division, whose latency is shorter on four values than on eight, and two vectors of four overlap)
MARCH_LANES = 4
_MARCH_VECTOR = ir.VectorType(_DOUBLE, MARCH_LANES)


def _fma(builder):
    """``fma(a, b, c) = a b + c`` on vectors of ``LANES`` values: one fused operation where the machine has
    it, a product and a sum where it has not (``llvm.fmuladd``, not ``llvm.fma``, which would call a slow
    exact emulation there)."""
    fn = cgutils.get_or_insert_function(builder.module, ir.FunctionType(_VECTOR, [_VECTOR] * 3),
                                        "llvm.fmuladd.v%df64" % LANES)
    return lambda a, b, c: builder.call(fn, [a, b, c])


def _vector_loop(builder, count, step, vector, name, body):
    """Emit ``for j in range(0, count, step): body(at)``, ``count`` a multiple of ``step``.

    ``at(ptr)`` is the pointer to the ``vector`` of values from ``ptr[j]`` on;
    ``body`` may add blocks of its own. The builder ends after the loop.
    """
    counted_loop(builder, count, step, name,
                 lambda j: body(lambda ptr: builder.bitcast(builder.gep(ptr, [j]), vector.as_pointer())))


#: the rows of the sample sums :func:`sample_rows` reads (``local``, see
#: :func:`microslip.kernels.aft_plane._sample_sums`): the local derivatives ``d11 = dT1/dt1, d12, d22,
#: c1 = dT1/dn, c2 = dT2/dn`` in rows 3 to 7, one for each of its six coefficient rows
LOCAL_ROWS = (3, 4, 6, 4, 5, 7)

#: the coefficients of one element at one sample in :func:`sample_rows`, in this order
SAMPLE_COEFFICIENTS = ("g11", "g12", "g13", "g22", "g23", "h1", "h2", "h3", "cb", "cp", "v1", "v2", "cy", "sb", "sp",
                       "full")


@intrinsic
def sample_rows(typingctx, U, m, B, Y, PT, coefs, local, order, count):  # pragma: no cover - compiled
    """Sample ``m`` of the sweep for the elements ``order[:count]``, over the ``nbp`` columns (a multiple of
    ``LANES``).

    ``U`` (Ns, 6, nbp), ``B`` (J, nbp), ``Y`` (J, 2, nbp), ``PT`` (Ns, nbp),
    ``coefs`` (16, Jp) and ``local`` (rows, Ns) C-contiguous
    float64, ``order`` int64. With element ``i``'s ``beta = B[i]``, ``y =
    Y[i]`` and coefficients ``coefs[:, i]`` (:data:`SAMPLE_COEFFICIENTS`,
    ``g21 = g12``; :func:`sample_coefficients`) and the sample's local
    derivative ``l_ab = local[LOCAL_ROWS[3a + b], m]``::

        U[m, 3a + b] = l_ab PT[m] + sum over the elements of (beta g_ab + y_a h_b)     (a = 0, 1; b = 0, 1, 2)
        y_a = (cb beta + cp PT[m]) v_a + cy y_a
        beta = sb beta + sp PT[m]

    An element whose ``full`` is 0 has ``beta = 0`` before and after (it
    slips or opens after a slip or an opening): its ``beta`` terms are left
    out. ``U[m]`` is written once, each element's rows read and written once.
    """
    sig = types.void(U, m, B, Y, PT, coefs, local, order, count)

    def codegen(context, builder, signature, args):
        # 512-bit vectors where the machine has them: LLVM otherwise splits these rows into 256-bit halves on
        # processors it tunes for 256-bit vectors (measured: the sweep 1.3x faster at J = 8, H = 7)
        set.add(builder.function.attributes, '"min-legal-vector-width"="512"')
        Uv, mv, bv, yv, pv, cv, lv, ov, nv = args
        Ua, ba, ya, pa, ca, la, oa = (context.make_array(signature.args[j])(context, builder, args[j])
                                      for j in (0, 2, 3, 4, 5, 6, 7))
        shape = cgutils.unpack_tuple(builder, Ua.shape, 3)
        nbp = shape[2]
        index = nbp.type

        def const(v):
            return ir.Constant(index, v)

        base = builder.mul(mv, builder.mul(shape[1], nbp))
        urows = [builder.gep(Ua.data, [builder.add(base, builder.mul(const(r), nbp))]) for r in range(6)]
        prow = builder.gep(pa.data, [builder.mul(mv, nbp)])
        fma = _fma(builder)

        Jp = cgutils.unpack_tuple(builder, ca.shape, 2)[1]

        samples = shape[0]
        local_terms = [splat(builder, builder.load(builder.gep(la.data, [builder.add(builder.mul(const(j), samples),
                                                                                     mv)])), _VECTOR)
                       for j in LOCAL_ROWS]

        def chunk(at):  # LANES columns
            pt = builder.load(at(prow), align=8)
            start = [builder.fmul(v, pt) for v in local_terms]
            chunks = builder.block
            elements = builder.append_basic_block("sample_rows.elements")
            stored = builder.append_basic_block("sample_rows.stored")
            builder.cbranch(builder.icmp_signed(">", nv, const(0)), elements, stored)
            # over the elements: the six sums stay in registers
            builder.position_at_end(elements)
            e = builder.phi(index)
            e.add_incoming(const(0), chunks)
            acc = [builder.phi(_VECTOR) for _ in range(6)]
            for a, v in zip(acc, start):
                a.add_incoming(v, chunks)
            i = builder.load(builder.gep(oa.data, [e]))

            def coefficient(j):
                return builder.load(builder.gep(ca.data, [builder.add(builder.mul(const(j), Jp), i)]))

            h1, h2, h3, cp, v1, v2, cy = (splat(builder, coefficient(j), _VECTOR) for j in (5, 6, 7, 9, 10, 11, 12))
            y1 = builder.gep(ya.data, [builder.mul(i, builder.add(nbp, nbp))])
            y2 = builder.gep(y1, [nbp])
            a1, a2 = (builder.load(at(ptr), align=8) for ptr in (y1, y2))
            h = (h1, h2, h3, h1, h2, h3)
            full = builder.append_basic_block("sample_rows.full")
            bare = builder.append_basic_block("sample_rows.bare")
            added = builder.append_basic_block("sample_rows.added")
            builder.cbranch(builder.fcmp_ordered("!=", coefficient(15), ir.Constant(_DOUBLE, 0.0)), full, bare)
            sums = {}
            for block in (full, bare):
                builder.position_at_end(block)
                news = [fma(a1 if r < 3 else a2, h[r], acc[r]) for r in range(6)]
                q = builder.fmul(pt, cp)
                if block is full:  # the beta terms
                    g11, g12, g13, g22, g23, cb, sb, sp = (splat(builder, coefficient(j), _VECTOR)
                                                           for j in (0, 1, 2, 3, 4, 8, 13, 14))
                    brow = builder.gep(ba.data, [builder.mul(i, nbp)])
                    bp = builder.load(at(brow), align=8)
                    news = [fma(bp, g, v) for g, v in zip((g11, g12, g13, g12, g22, g23), news)]
                    q = fma(cb, bp, q)
                    builder.store(fma(pt, sp, builder.fmul(sb, bp)), at(brow), align=8)
                builder.store(fma(q, v1, builder.fmul(cy, a1)), at(y1), align=8)
                builder.store(fma(q, v2, builder.fmul(cy, a2)), at(y2), align=8)
                builder.branch(added)
                sums[block] = (builder.block, news)
            builder.position_at_end(added)
            new = [builder.phi(_VECTOR) for _ in range(6)]
            for block_end, news in sums.values():
                for phi, v in zip(new, news):
                    phi.add_incoming(v, block_end)
            following = builder.add(e, const(1))
            for a, v in zip(acc, new):
                a.add_incoming(v, added)
            e.add_incoming(following, added)
            builder.cbranch(builder.icmp_signed("<", following, nv), elements, stored)
            # the column's six rows, written once
            builder.position_at_end(stored)
            totals = [builder.phi(_VECTOR) for _ in range(6)]
            for total, v, v0 in zip(totals, new, start):
                total.add_incoming(v0, chunks)
                total.add_incoming(v, added)
            for total, ptr in zip(totals, urows):
                builder.store(total, at(ptr), align=8)

        _vector_loop(builder, nbp, LANES, _VECTOR, "sample_rows", chunk)
        return context.get_dummy_value()

    return sig, codegen


#: elements per pass of :func:`period_march`: two vectors of ``MARCH_LANES`` marched side by side (their chains
#: of square root and division overlap); the march's rows are padded to a multiple of it
MARCH_PAIR = 2 * MARCH_LANES


def _plane_lanes(builder, sqrt_fn, par, state, tx, ty, nk0):
    """:func:`microslip.kernels.element.plane_step` on ``MARCH_LANES`` elements, with the period map's derivative.

    ``par`` the vectors ``kt, mu kn / kt, mu kn, kn, gap``; ``state`` ``s1, s2, c0 .. c3``; ``tx, ty, nk0``
    the sample's motion in every lane. Returns the new state and the records ``(code, alpha, v1, v2, T1,
    T2)`` (see :func:`period_march`).
    """
    V = _MARCH_VECTOR
    zero = ir.Constant(V, [0.0] * MARCH_LANES)
    one = ir.Constant(V, [1.0] * MARCH_LANES)
    two = ir.Constant(V, [2.0] * MARCH_LANES)
    mul, sub, add, select = builder.fmul, builder.fsub, builder.fadd, builder.select
    kt, rk, mkn, _, gap = par
    s1, s2, c0, c1, c2, c3 = state
    # plane_step, operation for operation
    nk, closed, r, dx, dy, dd2, slipped = stretch(builder, rk, gap, nk0, tx, ty, s1, s2)
    q = inverse_root(builder, dd2, sqrt_fn)
    al = mul(r, q)
    g = mul(mul(mkn, nk), q)
    T1 = select(closed, select(slipped, mul(g, dx), mul(kt, dx)), zero)
    T2 = select(closed, select(slipped, mul(g, dy), mul(kt, dy)), zero)
    n1 = select(closed, select(slipped, sub(tx, mul(mul(r, dx), q)), s1), tx)
    n2 = select(closed, select(slipped, sub(ty, mul(mul(r, dy), q)), s2), ty)
    code = select(closed, select(slipped, two, one), zero)
    # the period map's derivative: C <- alpha v v^T C in slip, kept in stick, 0 when open
    slip = builder.and_(closed, slipped)
    stick = builder.and_(closed, builder.xor(slipped, ir.Constant(slipped.type, [True] * MARCH_LANES)))
    v1 = mul(builder.fneg(dy), q)
    v2 = mul(dx, q)
    w1 = mul(al, add(mul(v1, c0), mul(v2, c2)))
    w2 = mul(al, add(mul(v1, c1), mul(v2, c3)))
    C = [select(slip, mul(vv, ww), select(stick, cc, zero))
         for vv, ww, cc in ((v1, w1, c0), (v1, w2, c1), (v2, w1, c2), (v2, w2, c3))]
    records = (code, select(slip, al, zero), select(slip, v1, zero), select(slip, v2, zero), T1, T2)
    return [n1, n2, *C], records


def _carry_over_samples(builder, Ns, name, initial, step):
    """Emit ``for k in range(Ns): values = step(k, values)`` (``Ns >= 1``), the values (a list) held in
    registers from ``initial`` on; returns them after the last sample. The builder ends after the loop."""
    index = Ns.type
    entry = builder.block
    loop = builder.append_basic_block(name + ".samples")
    done = builder.append_basic_block(name + ".done")
    builder.branch(loop)
    builder.position_at_end(loop)
    k = builder.phi(index)
    k.add_incoming(ir.Constant(index, 0), entry)
    values = [builder.phi(v.type) for v in initial]
    for phi, v in zip(values, initial):
        phi.add_incoming(v, entry)
    new = step(k, values)
    following = builder.add(k, ir.Constant(index, 1))
    k.add_incoming(following, builder.block)
    for phi, v in zip(values, new):
        phi.add_incoming(v, builder.block)
    builder.cbranch(builder.icmp_signed("<", following, Ns), loop, done)
    builder.position_at_end(done)
    return new


def _sum_over_samples(builder, Ns, name, count, add):
    """``count`` vector sums from zero over the samples: :func:`_carry_over_samples` with ``add(k, sums)``."""
    return _carry_over_samples(builder, Ns, name, [ir.Constant(_VECTOR, [0.0] * LANES)] * count, add)


def _lane_march(builder, Jp, Ns, name, start, sample, finish):
    """Emit a march over ``Ns`` samples (``Ns >= 1``) of ``Jp`` elements (a multiple of ``MARCH_PAIR``).

    Each pass takes ``MARCH_PAIR`` elements as two vectors of ``MARCH_LANES``
    side by side, their state held in registers from sample to sample:
    ``start(g)`` gives the state (a list of vectors) of the vector whose
    first element is ``g``, ``sample(g, k, state)`` emits sample ``k`` and
    gives the new state, ``finish(g, state)`` stores the state after the
    last sample. The builder ends after the march.
    """
    def one_pass(j):
        groups = (j, builder.add(j, ir.Constant(j.type, MARCH_LANES)))
        first = start(groups[0])
        size = len(first)

        def step(k, values):
            return [v for i, g in enumerate(groups) for v in sample(g, k, values[i * size:(i + 1) * size])]

        last = _carry_over_samples(builder, Ns, name, first + start(groups[1]), step)
        for i, g in enumerate(groups):
            finish(g, last[i * size:(i + 1) * size])

    counted_loop(builder, Jp, MARCH_PAIR, name, one_pass)


def _row_vector(builder, data, row, width, col):
    """Pointer to the ``MARCH_LANES`` values from ``data[row * width + col]`` on."""
    return builder.bitcast(builder.gep(data, [builder.add(builder.mul(row, width), col)]), _MARCH_VECTOR.as_pointer())


@intrinsic
def period_march(typingctx, par, st, rec, t1, t2, n):  # pragma: no cover - compiled
    """One period of the AFT's march on the plane for every element, ``MARCH_PAIR`` elements per pass.

    The arithmetic of :func:`microslip.kernels.element.plane_step`, operation for
    operation (no fused multiply-adds: the same numbers bit for bit; a
    compiled loop over the elements calling it stays one element at a time,
    see the module's note). Each pass marches two vectors of
    ``MARCH_LANES`` elements through every sample side by side, their
    sliders and derivatives held in registers between samples. Rows of
    ``Jp`` elements (a multiple of ``MARCH_PAIR``), all C-contiguous
    float64: ``par`` (5, Jp) ``kt, mu kn / kt, mu kn, kn, gap``; ``st``
    (6, Jp) the sliders ``s1, s2`` at the start of the period (updated to
    its end) and the period map's derivative so far ``C`` (2x2 per element,
    row-major, updated: ``alpha v v^T C`` in slip, unchanged in stick, 0
    when open); ``rec`` (6, Ns, Jp) receives at ``[:, k]`` the condition of
    sample ``k`` (0 open, 1 stick, 2 slip, as a float), ``alpha = r / |d|``
    and ``v = (-d2, d1) / |d|`` of a slip (0 otherwise) and the element's
    force ``T1, T2``. ``t1, t2, n`` (Ns,), ``Ns >= 1``, are the period's
    motion.
    """
    sig = types.void(par, st, rec, t1, t2, n)

    def codegen(context, builder, signature, args):
        pa, sa, ra, xa, ya, na = (context.make_array(signature.args[j])(context, builder, args[j]) for j in range(6))
        Jp = cgutils.unpack_tuple(builder, pa.shape, 2)[1]
        Ns = cgutils.unpack_tuple(builder, ra.shape, 3)[1]
        index = Jp.type
        V = _MARCH_VECTOR
        sqrt_fn = cgutils.get_or_insert_function(builder.module, ir.FunctionType(V, [V]),
                                                 "llvm.sqrt.v%df64" % MARCH_LANES)
        rows = [ir.Constant(index, r) for r in range(6)]
        pars = {}

        def start(g):
            pars[g] = [builder.load(_row_vector(builder, pa.data, rows[r], Jp, g), align=8) for r in range(5)]
            return [builder.load(_row_vector(builder, sa.data, rows[r], Jp, g), align=8) for r in range(6)]

        def sample(g, k, state):
            tx, ty, nk0 = (splat(builder, builder.load(builder.gep(a.data, [k])), V) for a in (xa, ya, na))
            new, records = _plane_lanes(builder, sqrt_fn, pars[g], state, tx, ty, nk0)
            for r, value in enumerate(records):
                builder.store(value, _row_vector(builder, ra.data, builder.add(builder.mul(rows[r], Ns), k), Jp, g),
                              align=8)
            return new

        def finish(g, state):
            for r, value in enumerate(state):
                builder.store(value, _row_vector(builder, sa.data, rows[r], Jp, g), align=8)

        _lane_march(builder, Jp, Ns, "period_march", start, sample, finish)
        return context.get_dummy_value()

    return sig, codegen


@intrinsic
def start_weights(typingctx, rec, nkt, weights, ends):  # pragma: no cover - compiled
    """Every element's coefficient ``Z = beta (x) I + z (x) w^T`` of its slider at the start of the period, as
    weights of the basis rows, ``MARCH_PAIR`` elements per pass.

    ``Z = sum_k -kt P[:, k] (x) C_k`` with ``C_k = A_k ... A_0``: the
    identity up to the first slip, ``c_k l_k w^T`` after it (``w`` the
    first slip's ``v``, ``l_k`` the last one's), zero from the first opening
    on. ``rec`` (6, Ns, Jp) are the periodic period's records
    (:func:`period_march`: condition, ``alpha``, ``v``), ``nkt`` (Jp) the
    elements' ``-kt``; ``weights`` (Ns, 3 Jp) receives at ``[k, i]`` the
    weight of ``P[:, k]`` in element ``i``'s ``beta`` and at ``[k, (1 + a) Jp
    + i]`` in its ``z_a``, so that one matrix product with ``P.T`` gives
    them all; ``ends`` (5, Jp) receives ``w1, w2, c, l1, l2``: ``w``, and
    ``Phi_s = C_(Ns-1) = c l w^T`` (``c = 1``, ``l = w = 0`` for an element
    that sticks throughout, whose ``Phi_s`` is the identity; ``c = 0`` once
    it opens). All C-contiguous float64.
    """
    sig = types.void(rec, nkt, weights, ends)

    def codegen(context, builder, signature, args):
        ra, ka, wa, ea = (context.make_array(signature.args[j])(context, builder, args[j]) for j in range(4))
        Ns, width = cgutils.unpack_tuple(builder, wa.shape, 2)
        Jp = cgutils.unpack_tuple(builder, ka.shape, 1)[0]
        index = Jp.type
        V = _MARCH_VECTOR
        zero = ir.Constant(V, [0.0] * MARCH_LANES)
        one = ir.Constant(V, [1.0] * MARCH_LANES)
        two = ir.Constant(V, [2.0] * MARCH_LANES)
        rows = [ir.Constant(index, r) for r in range(6)]
        mul, add, select = builder.fmul, builder.fadd, builder.select
        nkts = {}

        def start(g):
            nkts[g] = builder.load(_row_vector(builder, ka.data, rows[0], Jp, g), align=8)
            return [zero, zero, one, zero, zero, one, one]  # w1, w2, c, l1, l2, first, live

        def sample(g, k, state):
            w1, w2, cc, l1, l2, first, live = state
            code, al, v1, v2 = (builder.load(_row_vector(builder, ra.data, builder.add(builder.mul(rows[r], Ns), k),
                                                         Jp, g), align=8) for r in range(4))
            on = builder.and_(builder.fcmp_ordered("!=", live, zero), builder.fcmp_ordered("!=", code, zero))
            slip = builder.and_(on, builder.fcmp_ordered("==", code, two))
            was_first = builder.fcmp_ordered("!=", first, zero)
            grown = select(was_first, al, mul(cc, mul(al, add(mul(v1, l1), mul(v2, l2)))))
            cc = select(on, select(slip, grown, cc), zero)
            first_slip = builder.and_(slip, was_first)
            w1 = select(first_slip, v1, w1)
            w2 = select(first_slip, v2, w2)
            l1 = select(slip, v1, l1)
            l2 = select(slip, v2, l2)
            still = builder.and_(was_first, builder.xor(slip, ir.Constant(slip.type, [True] * MARCH_LANES)))
            f = mul(nkts[g], cc)
            moved = builder.and_(on, builder.xor(still, ir.Constant(still.type, [True] * MARCH_LANES)))
            for r, value in enumerate((select(builder.and_(on, still), nkts[g], zero), select(moved, mul(f, l1), zero),
                                       select(moved, mul(f, l2), zero))):
                builder.store(value, _row_vector(builder, wa.data, k, width, builder.add(builder.mul(rows[r], Jp), g)),
                              align=8)
            return [w1, w2, cc, l1, l2, select(still, one, zero), select(on, one, zero)]

        def finish(g, state):
            for r, value in enumerate(state[:5]):
                builder.store(value, _row_vector(builder, ea.data, rows[r], Jp, g), align=8)

        _lane_march(builder, Jp, Ns, "start_weights", start, sample, finish)
        return context.get_dummy_value()

    return sig, codegen


@intrinsic
def sample_coefficients(typingctx, coefs, rec, KR, w, m):  # pragma: no cover - compiled
    """Every element's coefficients for sample ``m`` of the sweep, ``MARCH_LANES`` elements at a time.

    ``coefs`` (16, Jp) receives :data:`SAMPLE_COEFFICIENTS` of each element
    (the rows :func:`sample_rows` reads); ``rec`` (6, Ns, Jp) is the
    periodic period's records (:func:`period_march`: condition, ``alpha``,
    ``v``), ``KR`` (2, Jp) the elements' ``kt`` and ``rk = mu kn / kt``,
    ``w`` (3, Jp) the ``w`` of each element's ``Y = beta I + y w^T``, set to
    ``v`` by a slip, and whether its ``beta`` is known to be zero (1: after
    a slip or an opening; 0: not known, or after a stick) for ``full``, 1
    when the ``beta`` terms are needed. With ``G = [I - alpha v v^T | -rk u]`` (``u = (v2,
    -v1)``; ``[I | 0]`` when open, where the records' ``alpha, v`` are 0)
    and ``h = w^T G``: ``g = G`` (``g21 = g12``), ``cb = alpha``, ``cp =
    -alpha kt``, ``cy = alpha w.v``, ``sb = sp = 0``; in stick ``g = h = 0``,
    ``cb = cp = v = 0``, ``cy = sb = 1``, ``sp = -kt`` (``y`` kept, ``beta -=
    kt P[:, m]``).
    """
    sig = types.void(coefs, rec, KR, w, m)

    def codegen(context, builder, signature, args):
        cv, rv, kv, wv, mv = args
        ca, ra, ka, wa = (context.make_array(signature.args[j])(context, builder, args[j]) for j in range(4))
        Jp = cgutils.unpack_tuple(builder, ca.shape, 2)[1]
        Ns = cgutils.unpack_tuple(builder, ra.shape, 3)[1]
        index = Jp.type

        def const(v):
            return ir.Constant(index, v)

        def row(data, r):
            return builder.gep(data, [builder.mul(const(r), Jp)])

        rrow = [builder.gep(ra.data, [builder.mul(builder.add(builder.mul(const(r), Ns), mv), Jp)]) for r in range(4)]
        V = _MARCH_VECTOR
        zero = ir.Constant(V, [0.0] * MARCH_LANES)
        one = ir.Constant(V, [1.0] * MARCH_LANES)
        mul, sub, add, select, neg = builder.fmul, builder.fsub, builder.fadd, builder.select, builder.fneg

        def lanes(at):
            code, al, v1, v2 = (builder.load(at(r), align=8) for r in rrow)
            kt, rk = (builder.load(at(row(ka.data, r)), align=8) for r in range(2))
            w1, w2, bare = (builder.load(at(row(wa.data, r)), align=8) for r in range(3))
            stick = builder.fcmp_ordered("==", code, one)
            wv = add(mul(w1, v1), mul(w2, v2))
            awv = mul(al, wv)
            slip = (sub(one, mul(mul(al, v1), v1)), neg(mul(mul(al, v1), v2)), neg(mul(rk, v2)),
                    sub(one, mul(mul(al, v2), v2)), mul(rk, v1), sub(w1, mul(awv, v1)), sub(w2, mul(awv, v2)),
                    neg(mul(rk, sub(mul(w1, v2), mul(w2, v1)))), al, neg(mul(al, kt)), v1, v2, awv, zero, zero)
            held = (zero,) * 12 + (one, one, neg(kt))
            for r, (a, b) in enumerate(zip(slip, held)):
                builder.store(select(stick, b, a), at(row(ca.data, r)), align=8)
            builder.store(select(stick, one, sub(one, bare)), at(row(ca.data, 15)), align=8)
            builder.store(select(stick, zero, one), at(row(wa.data, 2)), align=8)
            moved = builder.fcmp_ordered("==", code, ir.Constant(V, [2.0] * MARCH_LANES))
            builder.store(select(moved, v1, w1), at(row(wa.data, 0)), align=8)
            builder.store(select(moved, v2, w2), at(row(wa.data, 1)), align=8)

        _vector_loop(builder, Jp, MARCH_LANES, V, "sample_coefficients", lanes)
        return context.get_dummy_value()

    return sig, codegen


def _wide_arrays(context, builder, signature, args):
    """The array arguments of an intrinsic whose function may use 512-bit vectors (see :func:`sample_rows`)."""
    set.add(builder.function.attributes, '"min-legal-vector-width"="512"')
    return [context.make_array(t)(context, builder, a) for t, a in zip(signature.args, args)]


@intrinsic
def project_rows(typingctx, PT, X, out):  # pragma: no cover - compiled
    """``out[r] = X[r] @ PT`` for every row ``r``: each of the ``nbp`` sums in sample order, a product and then a
    sum (no fused multiply-add), as :func:`microslip.kernels.aft._project` adds them, to the bit.

    ``PT`` (Ns, nbp) (``nbp`` a multiple of ``LANES``), ``X`` (R, Ns) and
    ``out`` (R, nbp) C-contiguous float64. The ``nbp`` sums of a row go side
    by side in vectors, the row's values times the basis rows.
    """
    sig = types.void(PT, X, out)

    def codegen(context, builder, signature, args):
        pa, xa, oa = _wide_arrays(context, builder, signature, args)
        Ns, nbp = cgutils.unpack_tuple(builder, pa.shape, 2)
        R = cgutils.unpack_tuple(builder, xa.shape, 2)[0]
        with cgutils.for_range(builder, R) as rows:
            r = rows.index
            xrow = builder.gep(xa.data, [builder.mul(r, Ns)])
            orow = builder.gep(oa.data, [builder.mul(r, nbp)])

            def chunk(at):
                def add(k, sums):
                    pt = builder.load(at(builder.gep(pa.data, [builder.mul(k, nbp)])), align=8)
                    return [builder.fadd(sums[0], builder.fmul(pt, splat(builder, builder.load(builder.gep(xrow, [k])),
                                                                         _VECTOR)))]

                builder.store(_sum_over_samples(builder, Ns, "project_rows", 1, add)[0], at(orow), align=8)

            _vector_loop(builder, nbp, LANES, _VECTOR, "project_rows", chunk)
        return context.get_dummy_value()

    return sig, codegen


#: columns of the basis taken together by :func:`columns_times_basis` (its sums in registers: ``BLOCK`` vectors)
BLOCK = 8


@intrinsic
def columns_times_basis(typingctx, U, E, out):  # pragma: no cover - compiled
    """``out = E.T @ U``: ``out[q, r] = sum over m of E[m, q] U[m, r]``.

    ``U`` (Ns, R) (``R`` a multiple of ``LANES``), ``E`` (Ns, nq) (``nq`` a
    multiple of :data:`BLOCK`) and ``out`` (nq, R) C-contiguous float64
    (the history columns times the basis rows, the start weights times the
    basis rows). A small matrix product in registers: ``LANES`` columns of
    ``U`` times ``BLOCK`` columns of ``E`` at a time, with fused
    multiply-adds (at J = 8, H = 7 1.25x faster than the BLAS call with its
    set-up).
    """
    sig = types.void(U, E, out)

    def codegen(context, builder, signature, args):
        ua, ea, oa = _wide_arrays(context, builder, signature, args)
        Ns, R = cgutils.unpack_tuple(builder, ua.shape, 2)
        nq = cgutils.unpack_tuple(builder, ea.shape, 2)[1]
        index = R.type
        fma = _fma(builder)

        def const(v):
            return ir.Constant(index, v)

        def columns(at):
            blocks = builder.udiv(nq, const(BLOCK))
            with cgutils.for_range(builder, blocks) as qb:
                q0 = builder.mul(qb.index, const(BLOCK))

                def add(m, sums):
                    u = builder.load(at(builder.gep(ua.data, [builder.mul(m, R)])), align=8)
                    erow = builder.gep(ea.data, [builder.add(builder.mul(m, nq), q0)])
                    return [fma(u, splat(builder, builder.load(builder.gep(erow, [const(j)])), _VECTOR), v)
                            for j, v in enumerate(sums)]

                for j, v in enumerate(_sum_over_samples(builder, Ns, "columns_times_basis", BLOCK, add)):
                    builder.store(v, at(builder.gep(oa.data, [builder.mul(builder.add(q0, const(j)), R)])), align=8)

        _vector_loop(builder, R, LANES, _VECTOR, "columns_times_basis", columns)
        return context.get_dummy_value()

    return sig, codegen
