/*
 * picker.c - the light picker by power.  Since stage 03 the emitting
 * triangles are one light: a shading point picks one and divides by the
 * pick's probability (light_picker.h).  Stage 07 picks in proportion to
 * area; here in proportion to power (Shirley, Wang and Zimmerman, "Monte
 * Carlo Techniques for Direct Lighting Calculations", 1996), so a bright
 * triangle gets more of the rays than a dim one of its size, where picks
 * by area gave them as many (--no-light-pick).
 */
#include "light.h"

double
light_weight_power(const struct area_light *light)
{
    /* Power over pi: area x luminance, x 2 from both sides. */
    vec3 l = light->radiance;
    double luminance = 0.2126 * l.x + 0.7152 * l.y + 0.0722 * l.z;
    return (double)area_light_area(light) * luminance * (light->two_sided ? 2 : 1);
}
