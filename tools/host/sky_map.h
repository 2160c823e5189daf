/* SPDX-License-Identifier: MIT */
/* sky_map — an equirectangular environment map (Radiance .hdr) as the core's sky dome:
 * one sun a cell, carrying the map's light over the cell (rad_cli --sky-hdr; uses libm).
 *
 * The dome is the core's (rad.h RAD_LIGHT_SKY, lib/light.c): for N = 3 m^2 directions,
 * band i (0..m-1) holds the directions whose projection on the ground lies in the ring
 * of radii i / m .. (i + 1) / m of the unit disc, zenith angles asin(i / m) ..
 * asin((i + 1) / m), in 3 (2 i + 1) cells of equal azimuth, counted from the core's
 * frame for up +Y (rad__cube_frame: f0 = (-0.8, 0, -0.6), f1 = up x f0). Each cell's
 * light is integrated exactly from the map, taken as constant over each pixel: the
 * cell's and the pixel's rectangles in (zenith angle, azimuth) meet in a rectangle
 * over which the vector integral of w dw has a closed form, so a cell gets
 *   V = sum over pixels of L(pixel) x integral over (cell and pixel) of w dw
 * per channel, with no sampling. The cell's sun comes along the grey (channel sum) V's
 * direction with irradiance V.up / cos per channel, as the core's sky does: a plane
 * facing up then receives exactly the integral of L cos t dw over the sky, and any
 * plane that sees a whole cell the cell's light exactly (for a grey map). A black cell
 * gives no sun.
 *
 * The map: +Y up; row 0 (the top) is the zenith, the last row the nadir, zenith angle
 * t = pi (y + 1/2) / H at row y's centre; column x at azimuth a = 2 pi ((x + 1/2) / W
 * - 1/2), direction (sin t cos a, cos t, sin t sin a): the middle column looks toward
 * +X, a quarter further right toward +Z, the left and right edges toward -X (three.js's
 * equirectUv). The lower half (below the horizon) is not used: the scene's own ground
 * stands there.
 */
#ifndef RAD_TOOLS_SKY_MAP_H
#define RAD_TOOLS_SKY_MAP_H

#ifdef __cplusplus
extern "C" {
#endif

#define SKY_MAP_MAX_DIRS     768 /* the core's: 3 x 16^2 */
#define SKY_MAP_DEFAULT_DIRS 192

typedef struct {
    double dir[3]; /* the way its light travels, unit */
    double e[3];   /* irradiance on a plane facing it, per channel */
} sky_sun;

/* The dome's bands m for DIRS directions (0: the default), 3 m^2 <= DIRS, as the core's. */
int sky_map_bands(int dirs);

/* The map RGB (W x H x 3 linear floats, row 0 at the top, each >= 0) times SCALE over
 * the dome of DIRS directions (0: the default) into SUNS (room for 3 m^2), black cells
 * left out. Returns the count of suns, or -1 out of memory. */
int sky_map_suns(const float *rgb, int w, int h, double scale, int dirs, sky_sun *suns);

#ifdef __cplusplus
}
#endif

#endif
