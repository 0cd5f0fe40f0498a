/* main.c -- the core library's test suite (see harness.c). */
#include "test.h"

#define TESTS(X)                                                     \
    X(test_uniform_sky) X(test_sphere_over_plane) X(test_supersample) X(test_flat_blocker) X(test_box_closed_form)                    \
    X(test_rotational_gradient_sky) X(test_radius_rules) X(test_strata_directions) \
    X(test_pack_roundtrip) X(test_weighted_mean) X(test_blend_mean) X(test_strata_follow_accuracy) X(test_behind_relative)  \
    X(test_extrapolation) X(test_lookup_gradient_one) X(test_lookup_gradient_sphere) X(test_lookup_gradient_status) X(test_lookup_or_compute) X(test_open_sky_own_point) X(test_full_no_evict) \
    X(test_evict_clock) X(test_index_exact) X(test_weigh_fused) X(test_index_scales) X(test_index_grow_faces)          \
    X(test_config_checks) X(test_config_version) X(test_config_read_back) X(test_normals_both) X(test_normals_refused) X(test_version) X(test_footprints) X(test_defaults) X(test_init_block) \
    X(test_normal_any_length) X(test_bad_input_unchanged) X(test_callback_failures) X(test_overflow_radiance) X(test_ports) \
    X(test_threads_stress) X(test_threads_determinism)                 \
    X(test_visibility_sphere) X(test_visibility_box) X(test_visibility_open_sky) \
    X(test_sight_wall) X(test_sight_clear) X(test_sight_callback) X(test_sight_failure_unchanged) X(test_sight_convex) X(test_attach_bit_flips) X(test_attach_damaged) X(test_attach_open_pass_overfull) \
    X(test_occlusion_sphere) X(test_sh_orthonormal) X(test_sh_closed_forms)  \
    X(test_sh_gradient) X(test_sh_cap_closed_form) X(test_sh_emitter_gradient) \
    X(test_sh_irradiance_convolution) X(test_sh_glossy_zonal) X(test_sh_radiance_closed_form) \
    X(test_sh_surface_record) X(test_sh_surface_record_horizon) X(test_sh_lookup_by_hand) X(test_sh_bad_input) X(test_sh_footprint) \
    X(test_insert_range_overflow) \
    X(test_hard_scale_invariance) X(test_hard_hemispheres) X(test_hit_normal_any_length) X(test_hard_lookups) X(test_hard_full_cache) \
    X(test_footprint_bounds) X(test_footprint_size_t) X(test_radius_limits) X(test_gradient_channels) \
    X(test_index_origin) X(test_relocate) X(test_host_context) X(test_busy_waits) X(test_not_stored_counted) \
    X(test_hessian_closed_forms) X(test_hessian_reference) X(test_eigen2) X(test_hessian_radius) X(test_gradient_within_reach) X(test_ellipse_records) X(test_ellipse_axis_range) X(test_screen_bound) X(test_leak_guard_by_hand) \
    X(test_snapshot_round_trip) X(test_snapshot_round_trip_sh) X(test_snapshot_rejects) X(test_snapshot_other_strata) X(test_snapshot_by_hand) X(test_merge_order_free) \
    X(test_pass_order_free) X(test_pass_frozen) X(test_pass_full) X(test_pass_state) X(test_pass_lock_free) \
    X(test_share_processes) X(test_share_killed) X(test_share_killed_in_lock) X(test_share_zombie) X(test_port_owner_after_fork) X(test_share_killed_random) X(test_join_refused) \
    X(test_safe_defaults) X(test_index_clamped) X(test_index_compact) X(test_pass_end_incremental) X(test_index_reach_tight) X(test_index_bulk_spread) X(test_index_far_scales) X(test_index_far_from_origin) X(test_index_root_refused) \
    X(test_kind_occ_records) X(test_kind_occ_lookups) X(test_kind_occ_snapshot_attach) X(test_kind_occ_config) \
    X(test_levels_closed_form) X(test_levels_nested_refused) X(test_levels_cycle_refused) X(test_levels_threads) X(test_levels_cycle_threads) \
    X(test_detail_refined_strata) X(test_detail_full_grid_paths) X(test_detail_coarse_records) X(test_detail_config) X(test_detail_pixels_wall) X(test_detail_pixels_calls) X(test_detail_pixels_nested) X(test_detail_probes_flagged) X(test_pixel_footprint) X(test_pixel_footprint_lengths) X(test_pixel_footprint_mirror) \
    X(test_progress_rays_and_noise) X(test_progress_refines_stored) X(test_progress_refused) X(test_progress_callback_fails) X(test_progress_threads) X(test_progress_image_threads) X(test_pixel_kept) X(test_progress_pixel_records)

TESTS(TEST_DECL)

int main(int argc, char **argv)
{
    static const test_case all[] = {TESTS(TEST_ROW)};
    return test_run(all, sizeof all / sizeof all[0], argc, argv);
}
