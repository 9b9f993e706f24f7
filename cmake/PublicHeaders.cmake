# The headers `cmake --install` puts under <prefix>/include/clothref, relative to lib/clothref:
# what a program using clothref may include. Listed one by one: a new header is installed only
# when it is added here. The private ones are the SIMD bodies each per-ISA source file of fast/
# instantiates (*_impl.h) and the helpers shared by one area's sources (*_support.h); no public
# header includes them. cmake/Install.cmake fails the configuration on a header of lib/clothref
# in neither list; the package test (tests/package/run_package_test.cmake) checks that the install
# holds exactly the public list plus the generated trace/build_info.h, and compiles a file that
# includes every installed header against the install alone.
# Included by cmake/Install.cmake and tests/package/run_package_test.cmake.
set(CLOTHREF_PUBLIC_HEADERS
    clothref.h
    analysis/stability.h analysis/work_precision.h
    base/enum_table.h base/function_ref.h base/precision.h
    core/cloth.h core/integrator.h core/method.h core/particles.h core/spheres.h core/types.h
    core/world.h
    diff/diff.h
    fast/contact_filter.h fast/grid_springs.h fast/simd_path.h fast/sphere_cloth_contacts.h
    fast/spring_kernels.h fast/thread_pool.h
    formula/course_formulas.h
    golden/golden.h
    io/error.h io/files.h io/gzip_stream.h io/json_input.h io/limits.h io/output_file.h
    io/progress.h io/terminal_text.h
    record/record.h record/world_views.h
    scene/make_world.h scene/scene.h
    solver/backward_euler.h
    trace/body_view.h trace/format.h trace/hash.h trace/reader.h trace/step_line.h
    verify/analytic.h verify/odeint_peer.h verify/verify.h)
set(CLOTHREF_PRIVATE_HEADERS
    diff/diff_support.h fast/contact_filter_impl.h fast/spring_kernels_impl.h
    verify/check_support.h)
