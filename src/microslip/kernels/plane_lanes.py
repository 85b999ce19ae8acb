"""One step of the march on the contact plane in LLVM's vector form, eight elements at a time (private).

:func:`microslip.kernels.element.march_plane` calls :func:`step_lanes` once per sample. It repeats
:func:`microslip.kernels.element.plane_step`'s operations on vectors of ``LANES`` elements, operation for
operation (no fused multiply-adds: the same numbers bit for bit), and adds the elements' forces, normal
forces and friction work in element order, as the scalar loop does. Written as a compiled loop over the
elements, the compiler vectorises it only behind run-time checks that the rows it reads and writes do
not overlap, repeated at every sample; here the rows are known not to overlap, so there are no checks.

Three more things the scalar loop cannot do:

* ``mu kn / kt`` and ``mu kn`` are read from rows computed once per march (the same operations as
  ``plane_step``'s callers), so a step costs one square root and one division per slipping element;
* a vector of elements none of which slips (all stick or open) skips the square root and the division
  (``plane_step``'s result does not use them there: the same numbers), and when the slipping elements
  are all in one half of it only that half is divided (:func:`_reciprocal_roots`);
* each element's force and condition are stored from the vectors, interleaved with shuffles, rather
  than copied one number at a time in a second loop.

The parameter rows hold ``Jp`` elements, ``J`` rounded up to a multiple of ``LANES``; the padding
elements are open at every sample (:data:`PADDING`): their forces, normal forces and work are zeros,
which leave the sums unchanged (a sum that starts at ``+0.0`` is never ``-0.0``), and they are not
recorded.
"""

from __future__ import annotations

import math

from llvmlite import ir
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

#: elements per vector operation (eight: 20 % faster than four at J = 16 on a machine with 512-bit
#: vectors, the cost of the instructions around the square roots and divisions halved; LLVM splits
#: each operation in two where vectors are narrower, with the same results)
LANES = 8
HALF = LANES // 2
#: the parameter rows :func:`step_lanes` reads, in this order
PARAMETERS = ("kt", "rk", "mkn", "kn", "gap")
#: the parameters of a padding element, in the order of :data:`PARAMETERS`: its depth ``n - inf`` is
#: never positive (open), its normal force ``0 max(-inf, 0)`` is zero, and it never slips (its stick
#: radius ``0 (-inf)`` is NaN, and ``|d|^2 > NaN`` is false)
PADDING = (1.0, 0.0, 0.0, 0.0, math.inf)
#: the conditions recorded, those of :mod:`microslip.kernels.element` (which imports this module)
OPEN, STICK, SLIP = 0, 1, 2
#: the smallest ``|d|^2`` (m^2) the element update divides by (``2^-1000``: its reciprocal is finite); see
#: :func:`microslip.kernels.element.plane_step`
DD2_MIN = 2.0 ** -1000

_DOUBLE = ir.DoubleType()
_VECTOR = ir.VectorType(_DOUBLE, LANES)
_SUMS = ir.VectorType(_DOUBLE, 4)
_HALF = ir.VectorType(_DOUBLE, HALF)
_INT32 = ir.IntType(32)
_BYTE = ir.IntType(8)
_BYTES = ir.VectorType(_BYTE, LANES)


def splat(builder, x, vector=_VECTOR):
    """The scalar ``x`` in every lane of ``vector``."""
    v = builder.insert_element(ir.Constant(vector, ir.Undefined), x, ir.Constant(_INT32, 0))
    return builder.shuffle_vector(v, ir.Constant(vector, ir.Undefined),
                                  ir.Constant(ir.VectorType(_INT32, vector.count), [0] * vector.count))


def shuffle(builder, a, b, lanes):
    """``[concat(a, b)[i] for i in lanes]``."""
    return builder.shuffle_vector(a, b, ir.Constant(ir.VectorType(_INT32, len(lanes)), list(lanes)))


def _interleaved(h):
    """The lanes of ``shuffle(a, b, .)`` interleaving ``a`` and ``b`` over elements ``h HALF .. (h + 1) HALF - 1``."""
    return [v for i in range(h * HALF, (h + 1) * HALF) for v in (i, LANES + i)]


def counted_loop(builder, count, step, name, body):
    """Emit ``for j in range(0, count, step): body(j)``, ``count`` a multiple of ``step``.

    ``body`` may add blocks of its own; the builder ends after the loop.
    """
    index = count.type
    entry = builder.block
    loop = builder.append_basic_block(name + ".loop")
    done = builder.append_basic_block(name + ".done")
    builder.cbranch(builder.icmp_signed(">", count, ir.Constant(index, 0)), loop, done)
    builder.position_at_end(loop)
    j = builder.phi(index)
    j.add_incoming(ir.Constant(index, 0), entry)
    body(j)
    following = builder.add(j, ir.Constant(index, step))
    j.add_incoming(following, builder.block)
    builder.cbranch(builder.icmp_signed("<", following, count), loop, done)
    builder.position_at_end(done)


def _if(builder, condition, name, then):
    """Emit ``if condition: then()``; the builder ends after it."""
    done = builder.append_basic_block(name + ".done")
    taken = builder.append_basic_block(name + ".then")
    builder.cbranch(condition, taken, done)
    builder.position_at_end(taken)
    then()
    builder.branch(done)
    builder.position_at_end(done)


def inverse_root(builder, dd2, sqrt):
    """``1 / |d|`` as :func:`microslip.kernels.element.plane_step` computes it, on a vector ``dd2`` of ``|d|^2``:
    ``sqrt(dd2) (1 / max(dd2, DD2_MIN))``, the square root and the division side by side; ``sqrt`` is
    LLVM's square root for that vector type."""
    vector = dd2.type
    floor = ir.Constant(vector, [DD2_MIN] * vector.count)
    clamped = builder.select(builder.fcmp_ordered(">", dd2, floor), dd2, floor)
    return builder.fmul(builder.call(sqrt, [dd2]), builder.fdiv(ir.Constant(vector, [1.0] * vector.count), clamped))


def stretch(builder, rk, gap, n, tx, ty, s1, s2):
    """The start of :func:`microslip.kernels.element.plane_step` on vectors, operation for operation: ``(nk, closed,
    r, dx, dy, dd2, slipped)``, the depth ``n - gap``, whether it is positive, the stick radius ``rk nk``,
    the stretch ``d = t - s``, ``|d|^2`` and whether ``|d|^2 > r^2``."""
    nk = builder.fsub(n, gap)
    closed = builder.fcmp_ordered(">", nk, ir.Constant(nk.type, [0.0] * nk.type.count))
    r = builder.fmul(rk, nk)
    dx = builder.fsub(tx, s1)
    dy = builder.fsub(ty, s2)
    dd2 = builder.fadd(builder.fmul(dx, dx), builder.fmul(dy, dy))
    return nk, closed, r, dx, dy, dd2, builder.fcmp_ordered(">", dd2, builder.fmul(r, r))


def _reciprocal_roots(builder, dd2, slipping, sqrt):
    """``1 / |d|`` (:func:`inverse_root`) in the lanes whose bit is set in ``slipping`` (an integer of ``LANES``
    bits, not 0); undefined in the others.

    The divider takes as long for a half of the vector as for the whole, twice (it works on 256 bits at
    a time and is not pipelined): when only one half holds slipping elements, only that half is divided.
    """
    bits = slipping.type
    halves = [builder.icmp_unsigned("!=", builder.and_(slipping, ir.Constant(bits, (2**HALF - 1) << (h * HALF))),
                                    ir.Constant(bits, 0)) for h in range(2)]
    whole = builder.append_basic_block("roots.whole")
    split = builder.append_basic_block("roots.split")
    low = builder.append_basic_block("roots.low")
    high = builder.append_basic_block("roots.high")
    done = builder.append_basic_block("roots.done")
    builder.cbranch(builder.and_(*halves), whole, split)
    builder.position_at_end(whole)
    q_whole = inverse_root(builder, dd2, sqrt)
    builder.branch(done)
    builder.position_at_end(split)
    builder.cbranch(halves[0], low, high)
    half_sqrt = cgutils.get_or_insert_function(builder.module, ir.FunctionType(_HALF, [_HALF]),
                                               "llvm.sqrt.v%df64" % HALF)
    results = []
    for h, block in enumerate((low, high)):
        builder.position_at_end(block)
        part = _opaque(builder, shuffle(builder, dd2, dd2, list(range(h * HALF, (h + 1) * HALF))))
        qh = inverse_root(builder, part, half_sqrt)
        undefined = ir.Constant(_HALF, ir.Undefined)
        results.append(shuffle(builder, *((qh, undefined) if h == 0 else (undefined, qh)), list(range(LANES))))
        builder.branch(done)
    builder.position_at_end(done)
    q = builder.phi(_VECTOR)
    for v, block in zip((q_whole, *results), (whole, low, high)):
        q.add_incoming(v, block)
    return q


def _opaque(builder, v):
    """``v``, through an empty instruction LLVM cannot look into on x86 (so that it neither hoists the half's
    square root out of its branch nor merges it with the other half's); ``v`` elsewhere."""
    if not builder.module.triple.startswith(("x86_64", "i686", "i386")):
        return v
    return builder.asm(ir.FunctionType(v.type, [v.type]), "", "=v,0", [v], False)


def _elements(builder, par, sl, tx, ty, n, record):
    """Every element's step from the sample ``(tx, ty, n)``: the sliders ``sl`` updated, the sums
    ``(T1, T2, N, W)`` returned as a vector; ``record(j, pairs, T1, T2, N, moving)`` stores the records
    of elements ``j .. j + LANES - 1`` (or is None)."""
    Jp = cgutils.unpack_tuple(builder, par.shape, 2)[1]
    index = Jp.type
    prow = [builder.gep(par.data, [builder.mul(ir.Constant(index, r), Jp)]) for r in range(len(PARAMETERS))]
    srow = [builder.gep(sl.data, [builder.mul(ir.Constant(index, r), Jp)]) for r in range(2)]
    tx, ty, n0 = (splat(builder, v) for v in (tx, ty, n))
    zero = ir.Constant(_VECTOR, [0.0] * LANES)
    zeros = ir.Constant(_SUMS, [0.0] * 4)
    sqrt = cgutils.get_or_insert_function(builder.module, ir.FunctionType(_VECTOR, [_VECTOR]),
                                          "llvm.sqrt.v%df64" % LANES)
    mul, sub, add, select = builder.fmul, builder.fsub, builder.fadd, builder.select

    def maximum0(x):  # max(x, 0.0) as compiled: 0.0 if 0.0 > x else x
        return select(builder.fcmp_ordered(">", zero, x), zero, x)

    entry = builder.block
    sums = []

    def group(j):
        def at(ptr):
            return builder.bitcast(builder.gep(ptr, [j]), _VECTOR.as_pointer())

        acc = builder.phi(_SUMS)
        acc.add_incoming(zeros, entry)
        kt, rk, mkn, kn, gap = (builder.load(at(p), align=8) for p in prow)
        s1, s2 = (builder.load(at(p), align=8) for p in srow)
        nk, closed, r, dx, dy, dd2, slipped = stretch(builder, rk, gap, n0, tx, ty, s1, s2)
        moving = builder.and_(closed, slipped)  # the elements that slip: code == SLIP
        held = builder.block
        slipping = builder.append_basic_block("step_lanes.slip")
        joined = builder.append_basic_block("step_lanes.joined")
        mask_bits = builder.bitcast(moving, ir.IntType(LANES))
        builder.cbranch(builder.icmp_unsigned("!=", mask_bits, ir.Constant(ir.IntType(LANES), 0)), slipping, joined)
        builder.position_at_end(slipping)
        q = _reciprocal_roots(builder, dd2, mask_bits, sqrt)
        g = mul(mul(mkn, nk), q)
        slip = (mul(g, dx), mul(g, dy), sub(tx, mul(mul(r, dx), q)), sub(ty, mul(mul(r, dy), q)))
        slipping = builder.block
        builder.branch(joined)
        builder.position_at_end(joined)
        g1, g2, m1, m2 = (builder.phi(_VECTOR) for _ in slip)
        for phi, v in zip((g1, g2, m1, m2), slip):
            phi.add_incoming(v, slipping)
            phi.add_incoming(ir.Constant(_VECTOR, ir.Undefined), held)  # no element slips: never selected below
        T1 = select(closed, select(slipped, g1, mul(kt, dx)), zero)
        T2 = select(closed, select(slipped, g2, mul(kt, dy)), zero)
        n1 = select(closed, select(slipped, m1, s1), tx)
        n2 = select(closed, select(slipped, m2, s2), ty)
        N = mul(kn, maximum0(nk))
        W = maximum0(add(mul(T1, sub(n1, s1)), mul(T2, sub(n2, s2))))  # plane_work
        builder.store(n1, at(srow[0]), align=8)
        builder.store(n2, at(srow[1]), align=8)
        # each element's (T1, T2) and (N, W) side by side: pairs[h] and work[h] hold elements h HALF .. (h + 1) HALF - 1
        pairs = [shuffle(builder, T1, T2, _interleaved(h)) for h in range(2)]
        work = [shuffle(builder, N, W, _interleaved(h)) for h in range(2)]
        if record is not None:
            record(j, pairs, T1, T2, N, moving)
        # the sums in element order: the four quantities of one element in one vector
        total = acc
        for i in range(LANES):
            h, p = divmod(i, HALF)
            lanes = (2 * p, 2 * p + 1, LANES + 2 * p, LANES + 2 * p + 1)
            total = add(total, shuffle(builder, pairs[h], work[h], lanes))
        acc.add_incoming(total, builder.block)
        sums.append((total, builder.block))

    counted_loop(builder, Jp, LANES, "step_lanes", group)
    (total, latch), = sums
    result = builder.phi(_SUMS)
    result.add_incoming(zeros, entry)
    result.add_incoming(total, latch)
    return result


def _recorder(builder, Ti, cond, k):
    """``record(j, pairs, T1, T2, N, moving)``: elements ``j ..`` of sample ``k`` into ``Ti`` ``(steps, J, 2)``
    and ``cond`` ``(steps, J)`` (0 open, 1 stick, 2 slip, as the scalar march: open where ``N_i == 0``)."""
    J = cgutils.unpack_tuple(builder, cond.shape, 2)[1]
    index = J.type
    ti_row = builder.gep(Ti.data, [builder.mul(k, builder.add(J, J))])
    cond_row = builder.gep(cond.data, [builder.mul(k, J)])

    def record(j, pairs, T1, T2, N, moving):
        def codes(v):
            return ir.Constant(_BYTES, [v] * LANES)

        code = builder.select(builder.fcmp_ordered("==", N, ir.Constant(_VECTOR, [0.0] * LANES)), codes(OPEN),
                              builder.select(moving, codes(SLIP), codes(STICK)))
        ti = builder.gep(ti_row, [builder.add(j, j)])
        at_cond = builder.gep(cond_row, [j])
        whole = builder.icmp_signed("<=", builder.add(j, ir.Constant(index, LANES)), J)
        vectors = builder.append_basic_block("record.vectors")
        lanes = builder.append_basic_block("record.lanes")
        done = builder.append_basic_block("record.done")
        builder.cbranch(whole, vectors, lanes)
        builder.position_at_end(vectors)
        for h in range(2):
            builder.store(pairs[h], builder.bitcast(builder.gep(ti, [ir.Constant(index, h * LANES)]),
                                                    _VECTOR.as_pointer()), align=8)
        builder.store(code, builder.bitcast(at_cond, _BYTES.as_pointer()), align=1)
        builder.branch(done)
        builder.position_at_end(lanes)  # the last, partial vector: its elements below J one by one
        for e in range(LANES):
            def store(e=e):
                lane = ir.Constant(_INT32, e)
                builder.store(builder.extract_element(T1, lane), builder.gep(ti, [ir.Constant(index, 2 * e)]))
                builder.store(builder.extract_element(T2, lane), builder.gep(ti, [ir.Constant(index, 2 * e + 1)]))
                builder.store(builder.extract_element(code, lane), builder.gep(at_cond, [ir.Constant(index, e)]))
            _if(builder, builder.icmp_signed("<", builder.add(j, ir.Constant(index, e)), J), "record.lane", store)
        builder.branch(done)
        builder.position_at_end(done)

    return record


def _sums(context, builder, signature, total):
    return context.make_tuple(builder, signature.return_type,
                              [builder.extract_element(total, ir.Constant(_INT32, i)) for i in range(4)])


def _arrays(context, builder, signature, args, which):
    return [context.make_array(signature.args[i])(context, builder, args[i]) for i in which]


def _check_layout(*arrays):
    for a in arrays:
        if not isinstance(a, types.Array) or a.layout != "C":
            raise TypeError(f"step_lanes needs C-contiguous arrays, got {a}")


@intrinsic
def step_lanes(typingctx, par, sl, tx, ty, n):  # pragma: no cover - compiled
    """One sample ``(tx, ty, n)`` for every element: returns the sums ``(T1, T2, N, W)``.

    ``par`` (5, Jp): the rows of :data:`PARAMETERS` (``rk = (mu kn) / kt``,
    ``mkn = mu kn``; the padding elements :data:`PADDING`); ``sl`` (2, Jp):
    the sliders, updated. Both C-contiguous float64, ``Jp`` a multiple of
    :data:`LANES`. The sums are those of
    :func:`microslip.kernels.element.march_plane`: the elements' forces (N), normal
    forces (N) and friction work (J), added in element order.
    """
    _check_layout(par, sl)
    sig = types.UniTuple(types.float64, 4)(par, sl, tx, ty, n)

    def codegen(context, builder, signature, args):
        pa, sa = _arrays(context, builder, signature, args, (0, 1))
        return _sums(context, builder, signature, _elements(builder, pa, sa, *args[2:5], None))

    return sig, codegen


@intrinsic
def step_lanes_recorded(typingctx, par, sl, tx, ty, n, Ti, cond, k):  # pragma: no cover - compiled
    """:func:`step_lanes`, also storing each element's force into ``Ti[k]`` and its condition into ``cond[k]``.

    ``Ti`` (steps, J, 2) float64 and ``cond`` (steps, J) int8, C-contiguous:
    0 open (where ``N_i == 0``), 1 stick, 2 slip.
    """
    _check_layout(par, sl, Ti, cond)
    sig = types.UniTuple(types.float64, 4)(par, sl, tx, ty, n, Ti, cond, k)

    def codegen(context, builder, signature, args):
        pa, sa, ta, ca = _arrays(context, builder, signature, args, (0, 1, 5, 6))
        record = _recorder(builder, ta, ca, args[7])
        return _sums(context, builder, signature, _elements(builder, pa, sa, *args[2:5], record))

    return sig, codegen
