/* SPDX-License-Identifier: MIT */
/* rad — the float twin's names. Included by rad.h when RAD_FLOAT is 1: the twin
 * (librad_float.a) links beside the fixed library, so its symbols carry the prefix
 * radf_. A program calls the rad_ names in either build; a new public function gets
 * its line here. */
#ifndef RAD_FLOAT_NAMES_H
#define RAD_FLOAT_NAMES_H

#define rad_init_abi                radf_init_abi
#define rad_plan_polygon            radf_plan_polygon
#define rad_add_polygon             radf_add_polygon
#define rad_join_polygon            radf_join_polygon
#define rad_shoot                   radf_shoot
#define rad_unshot_fraction         radf_unshot_fraction
#define rad_ambient                 radf_ambient
#define rad_element_radiosity       radf_element_radiosity
#define rad_element_geometry        radf_element_geometry
#define rad_shade_vertices          radf_shade_vertices
#define rad_shade_elements          radf_shade_elements
#define rad_render                  radf_render
#define rad_restart                 radf_restart
#define rad_set_surface             radf_set_surface
#define rad_use_element_reflectance radf_use_element_reflectance
#define rad_set_element_reflectance radf_set_element_reflectance
#define rad_form_factors            radf_form_factors
#define rad_cull_build              radf_cull_build
#define rad_gather_cull             radf_gather_cull
#define rad_shoot_cull              radf_shoot_cull
#define rad_strerror                radf_strerror
#define rad_real_from_q16           radf_real_from_q16
#define rad_rows_compute            radf_rows_compute
#define rad_rows_shoot              radf_rows_shoot
#define rad_rows_gauss_seidel       radf_rows_gauss_seidel
#define rad_mix                     radf_mix
#define rad_ff_from_code            radf_ff_from_code
#define rad_shot_begin              radf_shot_begin
#define rad_shot_part               radf_shot_part
#define rad_shot_end                radf_shot_end
#define rad_gather_init             radf_gather_init
#define rad_gather                  radf_gather
#define rad_gather_sh               radf_gather_sh
#define rad_direct                  radf_direct
#define rad_shot_aim                radf_shot_aim
#define rad_shot_receive_part       radf_shot_receive_part
#define rad_batch_begin             radf_batch_begin
#define rad_batch_render            radf_batch_render
#define rad_batch_end               radf_batch_end
#define rad_batch_aim               radf_batch_aim
#define rad_batch_receive_part      radf_batch_receive_part
#define rad_use_lights              radf_use_lights
#define rad_add_light               radf_add_light
#define rad_set_light               radf_set_light

#endif
