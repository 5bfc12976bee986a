#include "kinematics/closed_form_batch.hpp"

#include <cmath>

#include "kinematics/lu6.hpp"

namespace stewart {

namespace {

// The fastest kernel built for this CPU.
VectorPath cpu_vector_path() {
#if defined(STEWART_HAVE_AVX2_KERNEL) && (defined(__x86_64__) || defined(__i386__))
    __builtin_cpu_init();
    if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma"))
        return VectorPath::portable;
#ifdef STEWART_HAVE_AVX512VL_KERNEL
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
        __builtin_cpu_supports("avx512dq"))
        return VectorPath::avx512vl;
#endif
    return VectorPath::avx2;
#else
    return VectorPath::portable;
#endif
}

// The place of each of J^T's rows after partial pivoting at the home pose (0, 0, home_height, 0,
// 0, 0); the natural order where that factorisation fails.
void home_row_slots(const PlatformGeometry &g, double home_height, int slot[6]) {
    double a[36];  // J^T, row-major: column k = (n_k, b_k x n_k / length)
    for (int k = 0; k < STEWART_LEGS; ++k) {
        double d[3];
        for (int i = 0; i < 3; ++i)
            d[i] = (i == 2 ? home_height : 0.0) + g.platform_points(i, k) - g.base_points(i, k);
        const double L = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        const double n[3] = {d[0] / L, d[1] / L, d[2] / L};
        const double b[3] = {g.platform_points(0, k), g.platform_points(1, k),
                             g.platform_points(2, k)};
        const double moment[3] = {b[1] * n[2] - b[2] * n[1], b[2] * n[0] - b[0] * n[2],
                                  b[0] * n[1] - b[1] * n[0]};
        for (int i = 0; i < 3; ++i) {
            a[6 * i + k] = n[i];
            a[6 * (i + 3) + k] = moment[i] / g.characteristic_length;
        }
    }
    int pivot[6], order[6];
    const bool factored = lu6_factor(a, pivot, order, lu6_largest(a));
    for (int i = 0; i < 6; ++i) slot[factored ? order[i] : i] = i;
}

}  // namespace

VectorPath fastest_vector_path() {
    static const VectorPath fastest = cpu_vector_path();
    return fastest;
}

VectorPath batch_vector_path(int fidelity) {
    const VectorPath fastest = fastest_vector_path();
    return fastest == VectorPath::avx512vl && fidelity == STEWART_MASSLESS ? VectorPath::avx2
                                                                           : fastest;
}

bool vector_path_available(VectorPath path) {  // (each path's CPU runs the ones before it)
    return int(path) <= int(fastest_vector_path());
}

QuadModel quad_model(const PlatformGeometry &g, const LumpedBody &body,
                     const Eigen::Vector3d &gravity, const stewart_params &p,
                     const stewart_inverse_options &o) {
    QuadModel m{};
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < STEWART_LEGS; ++k) {
            for (int l = 0; l < 4; ++l) {
                m.base[i][k][l] = g.base_points(i, k);
                m.platform[i][k][l] = g.platform_points(i, k);
            }
        }
    m.min_length = g.min_length;
    m.characteristic_length = g.characteristic_length;
    m.mass = body.mass;
    for (int i = 0; i < 3; ++i) {
        m.com[i] = body.com[i];
        m.gravity[i] = gravity[i];
        for (int j = 0; j < 3; ++j) m.inertia[i][j] = body.inertia(i, j);
    }
    for (int k = 0; k < STEWART_LEGS; ++k)
        for (int l = 0; l < 4; ++l) {
            m.stroke_min[k][l] = p.stroke_min[k];
            m.stroke_max[k][l] = p.stroke_max[k];
            m.length_offset[k][l] = p.length_offset[k];
        }
    m.warn_condition = o.warn_condition;
    m.singular_condition = o.singular_condition;
    m.massless = o.fidelity == STEWART_MASSLESS;
    home_row_slots(g, p.home_height, m.row_slot);
    return m;
}

unsigned closed_form_quad(VectorPath path, const QuadModel &m, const QuadRows &rows,
                          const stewart_inverse_batch_outputs &out, size_t row) {
#ifdef STEWART_HAVE_AVX512VL_KERNEL
    if (path == VectorPath::avx512vl) return closed_form_quad_avx512vl(m, rows, out, row);
#endif
#ifdef STEWART_HAVE_AVX2_KERNEL
    if (path == VectorPath::avx2) return closed_form_quad_avx2(m, rows, out, row);
#endif
    (void)path;
    return closed_form_quad_portable(m, rows, out, row);
}

size_t closed_form_quad_run(VectorPath path, const QuadModel &m, const QuadRows &rows,
                            const stewart_inverse_batch_outputs &out, size_t row, size_t blocks,
                            unsigned &left) {
#ifdef STEWART_HAVE_AVX512VL_KERNEL
    if (path == VectorPath::avx512vl)
        return closed_form_quad_avx512vl_run(m, rows, out, row, blocks, left);
#endif
#ifdef STEWART_HAVE_AVX2_KERNEL
    if (path == VectorPath::avx2) return closed_form_quad_avx2_run(m, rows, out, row, blocks, left);
#endif
    (void)path;
    return closed_form_quad_portable_run(m, rows, out, row, blocks, left);
}

}  // namespace stewart
