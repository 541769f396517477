// P/Invoke declarations for every function exported by libtpi (include/tpi.h, ABI 0.1), in
// the header's order, each with its C signature above it. Conventions:
//   - one library name, Cdecl everywhere, no LibraryImport (net48 must work too);
//   - size_t is UIntPtr; uint32_t is uint; uint64_t is ulong; uint8_t is byte;
//   - handles are SafeHandles (TpiX *) and `TpiX **out` is `out XHandle`;
//   - arrays are blittable (double[], uint[], byte[], struct[]): pinned for the call, so the
//     library reads and writes the managed memory directly; NULL is a null array;
//   - text goes out as NUL-terminated UTF-8 byte[] and comes back the same way (no string
//     marshalling, whose default encoding differs between .NET Framework and Mono/.NET);
//   - the ABI has no bool (flags are uint32_t 0/1), so no MarshalAs(U1) is needed.
// The tests (NativeBindingTests) check every entry point resolves in the real library.
using System;
using System.Runtime.InteropServices;

namespace Tpi.Native.Interop
{
    internal static class UnsafeNativeMethods
    {
        /// <summary>
        /// The native library: tpi.dll on Windows, libtpi.dylib on macOS, libtpi.so on Linux
        /// (the runtime adds prefix and suffix).
        /// </summary>
        internal const string Lib = "tpi";

        // ---- library ------------------------------------------------------------------

        // const char *tpi_version(void);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern IntPtr tpi_version();

        // const char *tpi_status_name(uint32_t status);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern IntPtr tpi_status_name(uint status);

        // enum TpiStatus tpi_last_error_message(char *buf, size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_last_error_message([Out] byte[] buf, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_options_default(struct TpiOptions *options);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_options_default(ref NativeOptions options);

        // ---- surfaces -----------------------------------------------------------------

        // enum TpiStatus tpi_surface_new_nurbs(size_t degree_u, size_t degree_v, size_t count_u,
        //     size_t count_v, const double *knots_u, size_t knots_u_len, const double *knots_v,
        //     size_t knots_v_len, const double *points, size_t points_len, const double *weights,
        //     size_t weights_len, struct TpiSurface **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_surface_new_nurbs(UIntPtr degree_u, UIntPtr degree_v, UIntPtr count_u, UIntPtr count_v,
            double[] knots_u, UIntPtr knots_u_len, double[] knots_v, UIntPtr knots_v_len,
            double[] points, UIntPtr points_len, double[] weights, UIntPtr weights_len, out SurfaceHandle @out);

        // enum TpiStatus tpi_surface_new_elliptic_paraboloid(double a, double b, double x0, double x1,
        //     double y0, double y1, struct TpiSurface **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_surface_new_elliptic_paraboloid(double a, double b, double x0, double x1, double y0, double y1, out SurfaceHandle @out);

        // enum TpiStatus tpi_surface_new_hyperbolic_paraboloid(double a, double b, double x0, double x1,
        //     double y0, double y1, struct TpiSurface **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_surface_new_hyperbolic_paraboloid(double a, double b, double x0, double x1, double y0, double y1, out SurfaceHandle @out);

        // enum TpiStatus tpi_surface_new_sphere_cap(double radius, double x0, double x1, double y0,
        //     double y1, struct TpiSurface **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_surface_new_sphere_cap(double radius, double x0, double x1, double y0, double y1, out SurfaceHandle @out);

        // enum TpiStatus tpi_surface_new_sphere_cap_square(double radius, double half_width,
        //     struct TpiSurface **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_surface_new_sphere_cap_square(double radius, double half_width, out SurfaceHandle @out);

        // enum TpiStatus tpi_surface_new_ellipsoid_cap(double a, double b, double c, double x0, double x1,
        //     double y0, double y1, struct TpiSurface **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_surface_new_ellipsoid_cap(double a, double b, double c, double x0, double x1, double y0, double y1, out SurfaceHandle @out);

        // enum TpiStatus tpi_surface_new_egg_crate(double amplitude, double x0, double x1, double y0,
        //     double y1, struct TpiSurface **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_surface_new_egg_crate(double amplitude, double x0, double x1, double y0, double y1, out SurfaceHandle @out);

        // enum TpiStatus tpi_surface_new_cylinder(double radius, double x0, double x1, double y0,
        //     double y1, struct TpiSurface **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_surface_new_cylinder(double radius, double x0, double x1, double y0, double y1, out SurfaceHandle @out);

        // enum TpiStatus tpi_surface_new_plane(double p, double q, double c0, double x0, double x1,
        //     double y0, double y1, struct TpiSurface **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_surface_new_plane(double p, double q, double c0, double x0, double x1, double y0, double y1, out SurfaceHandle @out);

        // void tpi_surface_free(struct TpiSurface *surface);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern void tpi_surface_free(IntPtr surface);

        // enum TpiStatus tpi_surface_with_units(const struct TpiSurface *surface, int32_t units,
        //     struct TpiSurface **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_surface_with_units(SurfaceHandle surface, int units, out SurfaceHandle @out);

        // enum TpiStatus tpi_surface_with_trim(const struct TpiSurface *surface, const double *outer_uv,
        //     size_t outer_len, const double *holes_uv, size_t holes_len,
        //     const size_t *hole_point_counts, size_t hole_count, struct TpiSurface **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_surface_with_trim(SurfaceHandle surface, double[] outerUv, UIntPtr outerLen,
            double[] holesUv, UIntPtr holesLen, UIntPtr[] holePointCounts, UIntPtr holeCount, out SurfaceHandle @out);

        // enum TpiStatus tpi_surface_new_polysurface(const struct TpiSurface *const *faces, size_t count,
        //     struct TpiSurface **out);
        // The faces go as raw handle values (SafeHandle[] does not marshal): the caller keeps
        // each SafeHandle alive and AddRef'd for the call (Surface.Join).
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_surface_new_polysurface(IntPtr[] faces, UIntPtr count, out SurfaceHandle @out);

        // enum TpiStatus tpi_surface_units(const struct TpiSurface *surface, int32_t *out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_surface_units(SurfaceHandle surface, out int @out);

        // enum TpiStatus tpi_surface_domain(const struct TpiSurface *surface, struct TpiDomain *out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_surface_domain(SurfaceHandle surface, out Domain @out);

        // enum TpiStatus tpi_surface_evaluate(const struct TpiSurface *surface, const double *uv,
        //     size_t uv_len, struct TpiSample *out, size_t out_capacity);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_surface_evaluate(SurfaceHandle surface, double[] uv, UIntPtr uv_len, [Out] Sample[] @out, UIntPtr out_capacity);

        // ---- patterns -----------------------------------------------------------------

        // enum TpiStatus tpi_pattern_new(const double *uv, size_t uv_len, struct TpiPattern **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_pattern_new(double[] uv, UIntPtr uv_len, out PatternHandle @out);

        // enum TpiStatus tpi_pattern_new_grid(size_t nu, size_t nv, struct TpiPattern **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_pattern_new_grid(UIntPtr nu, UIntPtr nv, out PatternHandle @out);

        // enum TpiStatus tpi_pattern_new_hex(size_t nu, size_t nv, struct TpiPattern **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_pattern_new_hex(UIntPtr nu, UIntPtr nv, out PatternHandle @out);

        // enum TpiStatus tpi_pattern_new_jitter(size_t nu, size_t nv, double amount, uint64_t seed,
        //     struct TpiPattern **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_pattern_new_jitter(UIntPtr nu, UIntPtr nv, double amount, ulong seed, out PatternHandle @out);

        // enum TpiStatus tpi_pattern_new_random(size_t count, uint64_t seed, struct TpiPattern **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_pattern_new_random(UIntPtr count, ulong seed, out PatternHandle @out);

        // enum TpiStatus tpi_pattern_new_poisson(double radius, uint64_t seed, struct TpiPattern **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_pattern_new_poisson(double radius, ulong seed, out PatternHandle @out);

        // enum TpiStatus tpi_pattern_new_from_spec(const char *spec, struct TpiPattern **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_pattern_new_from_spec(byte[] spec, out PatternHandle @out);

        // enum TpiStatus tpi_pattern_new_for_surface(const struct TpiSurface *surface, const char *spec,
        //     const struct TpiOptions *options, struct TpiPattern **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_pattern_new_for_surface(SurfaceHandle surface, byte[] spec, ref NativeOptions options, out PatternHandle @out);

        // (the same entry point with options = NULL, for the defaults)
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true, EntryPoint = "tpi_pattern_new_for_surface")]
        internal static extern Status tpi_pattern_new_for_surface_defaults(SurfaceHandle surface, byte[] spec, IntPtr nullOptions, out PatternHandle @out);

        // enum TpiStatus tpi_pattern_new_for_surface_with_progress(const struct TpiSurface *surface,
        //     const char *spec, const struct TpiOptions *options, TpiProgressCallback callback,
        //     void *user_data, struct TpiPattern **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_pattern_new_for_surface_with_progress(SurfaceHandle surface, byte[] spec, ref NativeOptions options, ProgressCallback callback, IntPtr userData, out PatternHandle @out);

        // (the same entry point with options = NULL, for the defaults)
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true, EntryPoint = "tpi_pattern_new_for_surface_with_progress")]
        internal static extern Status tpi_pattern_new_for_surface_with_progress_defaults(SurfaceHandle surface, byte[] spec, IntPtr nullOptions, ProgressCallback callback, IntPtr userData, out PatternHandle @out);

        // enum TpiStatus tpi_pattern_fit_report(const struct TpiPattern *pattern, struct TpiFitReport *out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_pattern_fit_report(PatternHandle pattern, ref FitReport @out);

        // enum TpiStatus tpi_pattern_hex_baseline(const struct TpiSurface *surface, double max_deviation,
        //     size_t max_points, const struct TpiOptions *options, size_t *count, double *deviation);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_pattern_hex_baseline(SurfaceHandle surface, double maxDeviation, UIntPtr maxPoints, IntPtr nullOptions, out UIntPtr count, out double deviation);

        // void tpi_pattern_free(struct TpiPattern *pattern);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern void tpi_pattern_free(IntPtr pattern);

        // enum TpiStatus tpi_pattern_point_count(const struct TpiPattern *pattern, size_t *out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_pattern_point_count(PatternHandle pattern, out UIntPtr @out);

        // enum TpiStatus tpi_pattern_points(const struct TpiPattern *pattern, double *out, size_t capacity,
        //     size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_pattern_points(PatternHandle pattern, [Out] double[] @out, UIntPtr capacity, out UIntPtr needed);

        // ---- discretisation -----------------------------------------------------------

        // enum TpiStatus tpi_discretise(const struct TpiSurface *surface, const struct TpiPattern *pattern,
        //     const struct TpiOptions *options, struct TpiDiscretisation **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretise(SurfaceHandle surface, PatternHandle pattern, ref NativeOptions options, out DiscretisationHandle @out);

        // (the same entry point with options = NULL, for the defaults)
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true, EntryPoint = "tpi_discretise")]
        internal static extern Status tpi_discretise_defaults(SurfaceHandle surface, PatternHandle pattern, IntPtr nullOptions, out DiscretisationHandle @out);

        // typedef int32_t (*TpiProgressCallback)(void *user_data, uint32_t stage, uint64_t done, uint64_t total);
        [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
        internal delegate int ProgressCallback(IntPtr userData, uint stage, ulong done, ulong total);

        // enum TpiStatus tpi_discretise_with_progress(const struct TpiSurface *surface,
        //     const struct TpiPattern *pattern, const struct TpiOptions *options,
        //     TpiProgressCallback callback, void *user_data, struct TpiDiscretisation **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretise_with_progress(SurfaceHandle surface, PatternHandle pattern, ref NativeOptions options, ProgressCallback callback, IntPtr userData, out DiscretisationHandle @out);

        // (the same entry point with options = NULL, for the defaults)
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true, EntryPoint = "tpi_discretise_with_progress")]
        internal static extern Status tpi_discretise_with_progress_defaults(SurfaceHandle surface, PatternHandle pattern, IntPtr nullOptions, ProgressCallback callback, IntPtr userData, out DiscretisationHandle @out);

        // void tpi_discretisation_free(struct TpiDiscretisation *discretisation);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern void tpi_discretisation_free(IntPtr discretisation);

        // enum TpiStatus tpi_discretisation_facet_count(const struct TpiDiscretisation *discretisation, size_t *out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretisation_facet_count(DiscretisationHandle discretisation, out UIntPtr @out);

        // enum TpiStatus tpi_discretisation_vertex_count(const struct TpiDiscretisation *discretisation, size_t *out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretisation_vertex_count(DiscretisationHandle discretisation, out UIntPtr @out);

        // enum TpiStatus tpi_discretisation_vertices(const struct TpiDiscretisation *discretisation,
        //     double *out, size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretisation_vertices(DiscretisationHandle discretisation, [Out] double[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_discretisation_facet_sizes(const struct TpiDiscretisation *discretisation,
        //     uint32_t *out, size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretisation_facet_sizes(DiscretisationHandle discretisation, [Out] uint[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_discretisation_facet_indices(const struct TpiDiscretisation *discretisation,
        //     uint32_t *out, size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretisation_facet_indices(DiscretisationHandle discretisation, [Out] uint[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_discretisation_facet_flags(const struct TpiDiscretisation *discretisation,
        //     uint8_t *out, size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretisation_facet_flags(DiscretisationHandle discretisation, [Out] byte[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_discretisation_seeds(const struct TpiDiscretisation *discretisation,
        //     struct TpiSeed *out, size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretisation_seeds(DiscretisationHandle discretisation, [Out] Seed[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_discretisation_planes(const struct TpiDiscretisation *discretisation,
        //     struct TpiPlane *out, size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretisation_planes(DiscretisationHandle discretisation, [Out] FacetPlane[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_discretisation_neighbour_pairs(const struct TpiDiscretisation *discretisation,
        //     uint32_t *out, size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretisation_neighbour_pairs(DiscretisationHandle discretisation, [Out] uint[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_discretisation_dual_triangles(const struct TpiDiscretisation *discretisation,
        //     uint32_t *out, size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretisation_dual_triangles(DiscretisationHandle discretisation, [Out] uint[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_discretisation_quality(const struct TpiDiscretisation *discretisation,
        //     struct TpiQualityReport *out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretisation_quality(DiscretisationHandle discretisation, ref QualityReport @out);

        // enum TpiStatus tpi_discretisation_quality_json(const struct TpiDiscretisation *discretisation,
        //     char *out, size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretisation_quality_json(DiscretisationHandle discretisation, [Out] byte[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_discretisation_diagnostic_count(const struct TpiDiscretisation *discretisation,
        //     size_t *out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretisation_diagnostic_count(DiscretisationHandle discretisation, out UIntPtr @out);

        // enum TpiStatus tpi_discretisation_diagnostic_entries(const struct TpiDiscretisation *discretisation,
        //     struct TpiDiagnosticEntry *out, size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretisation_diagnostic_entries(DiscretisationHandle discretisation, [Out] DiagnosticEntry[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_discretisation_diagnostics_json(const struct TpiDiscretisation *discretisation,
        //     char *out, size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretisation_diagnostics_json(DiscretisationHandle discretisation, [Out] byte[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_discretisation_json(const struct TpiDiscretisation *discretisation,
        //     uint32_t include_timings, char *out, size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discretisation_json(DiscretisationHandle discretisation, uint include_timings, [Out] byte[] @out, UIntPtr capacity, out UIntPtr needed);

        // ---- fabrication ----------------------------------------------------------------

        // enum TpiStatus tpi_fabricate(const struct TpiDiscretisation *discretisation, double thickness,
        //     uint32_t side, uint32_t slots_per_edge, double sheet_width, double sheet_height, double gap,
        //     struct TpiFabrication **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_fabricate(DiscretisationHandle discretisation, double thickness, uint side, uint slots_per_edge, double sheet_width, double sheet_height, double gap, out FabricationHandle @out);

        // void tpi_fabrication_free(struct TpiFabrication *fabrication);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern void tpi_fabrication_free(IntPtr fabrication);

        // enum TpiStatus tpi_fabrication_counts(const struct TpiFabrication *fabrication, size_t *panels, size_t *sheets);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_fabrication_counts(FabricationHandle fabrication, out UIntPtr panels, out UIntPtr sheets);

        // enum TpiStatus tpi_fabrication_file(const struct TpiFabrication *fabrication, uint32_t file,
        //     char *out, size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_fabrication_file(FabricationHandle fabrication, uint file, [Out] byte[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_fabrication_gcode(const struct TpiFabrication *fabrication, double tool_diameter,
        //     char *out, size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_fabrication_gcode(FabricationHandle fabrication, double tool_diameter, [Out] byte[] @out, UIntPtr capacity, out UIntPtr needed);

        // ---- discrete surface ---------------------------------------------------------

        // enum TpiStatus tpi_discrete_surface_new(const struct TpiSurface *surface,
        //     const struct TpiPattern *pattern, const struct TpiOptions *options,
        //     struct TpiDiscreteSurface **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discrete_surface_new(SurfaceHandle surface, PatternHandle pattern, ref NativeOptions options, out DiscreteSurfaceHandle @out);

        // (the same entry point with options = NULL, for the defaults)
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true, EntryPoint = "tpi_discrete_surface_new")]
        internal static extern Status tpi_discrete_surface_new_defaults(SurfaceHandle surface, PatternHandle pattern, IntPtr nullOptions, out DiscreteSurfaceHandle @out);

        // void tpi_discrete_surface_free(struct TpiDiscreteSurface *discrete_surface);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern void tpi_discrete_surface_free(IntPtr discrete_surface);

        // enum TpiStatus tpi_discrete_surface_point_count(const struct TpiDiscreteSurface *discrete_surface,
        //     size_t *out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discrete_surface_point_count(DiscreteSurfaceHandle discrete_surface, out UIntPtr @out);

        // enum TpiStatus tpi_discrete_surface_points(const struct TpiDiscreteSurface *discrete_surface,
        //     double *out, size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discrete_surface_points(DiscreteSurfaceHandle discrete_surface, [Out] double[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_discrete_surface_move_point(struct TpiDiscreteSurface *discrete_surface,
        //     size_t index, double s, double t);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discrete_surface_move_point(DiscreteSurfaceHandle discrete_surface, UIntPtr index, double s, double t);

        // enum TpiStatus tpi_discrete_surface_add_point(struct TpiDiscreteSurface *discrete_surface,
        //     double s, double t, size_t *index);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discrete_surface_add_point(DiscreteSurfaceHandle discrete_surface, double s, double t, out UIntPtr index);

        // enum TpiStatus tpi_discrete_surface_remove_point(struct TpiDiscreteSurface *discrete_surface,
        //     size_t index);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discrete_surface_remove_point(DiscreteSurfaceHandle discrete_surface, UIntPtr index);

        // enum TpiStatus tpi_discrete_surface_set_surface(struct TpiDiscreteSurface *discrete_surface,
        //     const struct TpiSurface *surface);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discrete_surface_set_surface(DiscreteSurfaceHandle discrete_surface, SurfaceHandle surface);

        // enum TpiStatus tpi_discrete_surface_pending_edits(const struct TpiDiscreteSurface *discrete_surface,
        //     size_t *out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discrete_surface_pending_edits(DiscreteSurfaceHandle discrete_surface, out UIntPtr @out);

        // enum TpiStatus tpi_discrete_surface_recompute(struct TpiDiscreteSurface *discrete_surface);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discrete_surface_recompute(DiscreteSurfaceHandle discrete_surface);

        // enum TpiStatus tpi_discrete_surface_mesh(const struct TpiDiscreteSurface *discrete_surface,
        //     struct TpiDiscretisation **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discrete_surface_mesh(DiscreteSurfaceHandle discrete_surface, out DiscretisationHandle @out);

        // enum TpiStatus tpi_discrete_surface_changes(struct TpiDiscreteSurface *discrete_surface,
        //     struct TpiMeshChanges **out);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_discrete_surface_changes(DiscreteSurfaceHandle discrete_surface, out MeshChangesHandle @out);

        // void tpi_mesh_changes_free(struct TpiMeshChanges *changes);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern void tpi_mesh_changes_free(IntPtr changes);

        // enum TpiStatus tpi_mesh_changes_counts(const struct TpiMeshChanges *changes, uint32_t *everything,
        //     size_t *facet_count, size_t *vertex_id_bound);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_mesh_changes_counts(MeshChangesHandle changes, out uint everything, out UIntPtr facet_count, out UIntPtr vertex_id_bound);

        // enum TpiStatus tpi_mesh_changes_facets(const struct TpiMeshChanges *changes, uint32_t *out,
        //     size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_mesh_changes_facets(MeshChangesHandle changes, [Out] uint[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_mesh_changes_facet_sizes(const struct TpiMeshChanges *changes, uint32_t *out,
        //     size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_mesh_changes_facet_sizes(MeshChangesHandle changes, [Out] uint[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_mesh_changes_facet_indices(const struct TpiMeshChanges *changes, uint32_t *out,
        //     size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_mesh_changes_facet_indices(MeshChangesHandle changes, [Out] uint[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_mesh_changes_planes(const struct TpiMeshChanges *changes, struct TpiPlane *out,
        //     size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_mesh_changes_planes(MeshChangesHandle changes, [Out] FacetPlane[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_mesh_changes_vertex_ids(const struct TpiMeshChanges *changes, uint32_t *out,
        //     size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_mesh_changes_vertex_ids(MeshChangesHandle changes, [Out] uint[] @out, UIntPtr capacity, out UIntPtr needed);

        // enum TpiStatus tpi_mesh_changes_vertices(const struct TpiMeshChanges *changes, double *out,
        //     size_t capacity, size_t *needed);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl, ExactSpelling = true)]
        internal static extern Status tpi_mesh_changes_vertices(MeshChangesHandle changes, [Out] double[] @out, UIntPtr capacity, out UIntPtr needed);
    }
}
