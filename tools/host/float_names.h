/* SPDX-License-Identifier: MIT */
/* rad host glue: compiled with RAD_FLOAT=1, a file that includes this before
 * host/scene.h defines and calls the float twin's functions (scf_*, declared in
 * host/scene_float.h) under the names of the fixed build. Only the files built once
 * per build of the core include it: tools/host/scene.c, tools/host/parallel.c,
 * tools/bake/gltf_export.c, tools/host/tex_render.c, tools/host/ply_export.c,
 * tools/host/fgather.c and
 * tools/cli/rad_cli.c. */
#ifndef RAD_TOOLS_FLOAT_NAMES_H
#define RAD_TOOLS_FLOAT_NAMES_H

#define RAD_HOST_FLOAT_NAMES 1
#define sc_solver scf_solver
#define sc_solution scf_solution
#define sc_create scf_create
#define sc_destroy scf_destroy
#define sc_element_limit scf_element_limit
#define sc_solve scf_solve
#define sc_solve_started scf_solve_started
#define sc_set_memory_limit scf_set_memory_limit
#define sc_gauss_seidel_check scf_gauss_seidel_check
#define sc_get_stats scf_get_stats
#define sc_element_rgb scf_element_rgb
#define sc_element_area scf_element_area
#define sc_element_centroid scf_element_centroid
#define sc_element_tag scf_element_tag
#define sc_set_element_rho scf_set_element_rho
#define sc_element_rho scf_element_rho
#define sc_texture_elements scf_texture_elements
#define sc_element_vertices scf_element_vertices
#define sc_vertex_pos scf_vertex_pos
#define sc_shade scf_shade
#define sc_shade_elements scf_shade_elements
#define sc_render scf_render
#define sc_render_values scf_render_values
#define sc_form_factors scf_form_factors
#define sc_checksum scf_checksum
#define sc_core scf_core
#define sc_patch_count scf_patch_count
#define sc_patch scf_patch
#define sc_rows_compute scf_rows_compute
#define sc_rows_save scf_rows_save
#define sc_rows_load scf_rows_load
#define sc_get_rows_stats scf_get_rows_stats
#define sc_rows_solve scf_rows_solve
#define sc_rows_gauss_seidel scf_rows_gauss_seidel
#define sc_set_surfaces scf_set_surfaces
#define sc_restart scf_restart
#define sc_keep scf_keep
#define sc_solution_free scf_solution_free
#define sc_mix scf_mix
#define sc_solve_parallel scf_solve_parallel
#define sc_solve_batch scf_solve_batch
#define sc_gatherer scf_gatherer
#define sc_gatherer_new scf_gatherer_new
#define sc_gatherer_free scf_gatherer_free
#define sc_gather scf_gather
#define sc_gather_on scf_gather_on
#define sc_gather_sh scf_gather_sh
#define sc_gatherer_saturations scf_gatherer_saturations
#define sc_corner_light scf_corner_light
#define sc_corner_light_fg scf_corner_light_fg
#define sc_export_gltf scf_export_gltf
#define sc_export_ply scf_export_ply
#define sc_export_gltf_lightmap scf_export_gltf_lightmap
#define sc_render_textured scf_render_textured
#define sc_texture_detail scf_texture_detail
#define sc_render_surfaces scf_render_surfaces
#define sc_split_fn scf_split_fn
#define sc_gather_split scf_gather_split
#define sc_fgather scf_fgather
#define sc_fgather_new scf_fgather_new
#define sc_fgather_free scf_fgather_free
#define sc_fgather_progress scf_fgather_progress
#define sc_fgather_vertices scf_fgather_vertices
#define sc_vertex_colours scf_vertex_colours
#define sc_fgather_render scf_fgather_render

#endif
