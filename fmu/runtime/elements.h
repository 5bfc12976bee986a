/*
 * Expands the library's parameter and option tables (stewart/stewart_table.h: STEWART_PARAM_TABLE,
 * STEWART_OPTION_TABLE, STEWART_PLANT_OPTION_TABLE) into a model's variable families, one FMU variable per element:
 * element e of parameter `name` with id `id` becomes value reference id + e, variable
 * "name[e+1]" (or "name" if it has one element), C identifier name_<e+1>, struct field
 * name[e] (or name), and the table's description with the element's suffix (" x", " y", " z";
 * " of leg k"; " x of leg k"), exactly as the library names its elements. Used by a model's
 * variables.def:
 *
 *     STEWART_PARAM_TABLE(FMU_PARAM_FROM_TABLE)
 *     STEWART_OPTION_TABLE(FMU_OPTION_FROM_TABLE)
 *     STEWART_PLANT_OPTION_TABLE(FMU_PLANT_OPTION_FROM_TABLE)
 *
 * which calls FMU_PARAM(vr, id, "name", field, "unit", "displayUnit", "description") per element
 * and FMU_OPTION_INT(vr, id, "name", start, min, max, "description") or
 * FMU_OPTION_REAL(vr, id, "name", field, "unit", "description") per option. Element counts are
 * 1, 3, 6, 18 and STEWART_POSE_ELEMENTS (the table's).
 */
#ifndef STEWART_FMU_ELEMENTS_H
#define STEWART_FMU_ELEMENTS_H

#define FMU_PARAM_FROM_TABLE(id, name, count, unit, display, min, min_closed, max, max_closed, \
                             defaults, description)                                            \
    FMU_ELEMENTS_##count(id, name, unit, display, description)

#define FMU_ELEMENTS_1(id, name, unit, display, description) \
    FMU_PARAM(id, name, #name, name, unit, display, description)
#define FMU_ELEMENT_(id, e, k, name, unit, display, description) \
    FMU_PARAM((id) + e, name##_##k, #name "[" #k "]", name[e], unit, display, description)
#define FMU_ELEMENTS_3(id, name, unit, display, description)      \
    FMU_ELEMENT_(id, 0, 1, name, unit, display, description " x") \
    FMU_ELEMENT_(id, 1, 2, name, unit, display, description " y") \
    FMU_ELEMENT_(id, 2, 3, name, unit, display, description " z")
#define FMU_ELEMENTS_6(id, name, unit, display, description)             \
    FMU_ELEMENT_(id, 0, 1, name, unit, display, description " of leg 1") \
    FMU_ELEMENT_(id, 1, 2, name, unit, display, description " of leg 2") \
    FMU_ELEMENT_(id, 2, 3, name, unit, display, description " of leg 3") \
    FMU_ELEMENT_(id, 3, 4, name, unit, display, description " of leg 4") \
    FMU_ELEMENT_(id, 4, 5, name, unit, display, description " of leg 5") \
    FMU_ELEMENT_(id, 5, 6, name, unit, display, description " of leg 6")

/* A pose (count STEWART_POSE_ELEMENTS in the table): x, y, z in m,
 * roll, pitch, yaw in rad shown in deg. */
#define FMU_POSE_ELEMENT_(id, e, k, name, axis, unit, display, description) \
    FMU_PARAM((id) + e, name##_##k, #name "[" #k "]", name[e], unit, display, description " " axis)
#define FMU_ELEMENTS_STEWART_POSE_ELEMENTS(id, name, unit, display, description) \
    FMU_POSE_ELEMENT_(id, 0, 1, name, "x", "m", "", description)                 \
    FMU_POSE_ELEMENT_(id, 1, 2, name, "y", "m", "", description)                 \
    FMU_POSE_ELEMENT_(id, 2, 3, name, "z", "m", "", description)                 \
    FMU_POSE_ELEMENT_(id, 3, 4, name, "roll", "rad", "deg", description)         \
    FMU_POSE_ELEMENT_(id, 4, 5, name, "pitch", "rad", "deg", description)        \
    FMU_POSE_ELEMENT_(id, 5, 6, name, "yaw", "rad", "deg", description)
/* x, y, z of legs 1..6 (joint coordinates and Cardan axes). */
#define FMU_ELEMENTS_18(id, name, unit, display, description)                \
    FMU_ELEMENT_(id, 0, 1, name, unit, display, description " x of leg 1")   \
    FMU_ELEMENT_(id, 1, 2, name, unit, display, description " y of leg 1")   \
    FMU_ELEMENT_(id, 2, 3, name, unit, display, description " z of leg 1")   \
    FMU_ELEMENT_(id, 3, 4, name, unit, display, description " x of leg 2")   \
    FMU_ELEMENT_(id, 4, 5, name, unit, display, description " y of leg 2")   \
    FMU_ELEMENT_(id, 5, 6, name, unit, display, description " z of leg 2")   \
    FMU_ELEMENT_(id, 6, 7, name, unit, display, description " x of leg 3")   \
    FMU_ELEMENT_(id, 7, 8, name, unit, display, description " y of leg 3")   \
    FMU_ELEMENT_(id, 8, 9, name, unit, display, description " z of leg 3")   \
    FMU_ELEMENT_(id, 9, 10, name, unit, display, description " x of leg 4")  \
    FMU_ELEMENT_(id, 10, 11, name, unit, display, description " y of leg 4") \
    FMU_ELEMENT_(id, 11, 12, name, unit, display, description " z of leg 4") \
    FMU_ELEMENT_(id, 12, 13, name, unit, display, description " x of leg 5") \
    FMU_ELEMENT_(id, 13, 14, name, unit, display, description " y of leg 5") \
    FMU_ELEMENT_(id, 14, 15, name, unit, display, description " z of leg 5") \
    FMU_ELEMENT_(id, 15, 16, name, unit, display, description " x of leg 6") \
    FMU_ELEMENT_(id, 16, 17, name, unit, display, description " y of leg 6") \
    FMU_ELEMENT_(id, 17, 18, name, unit, display, description " z of leg 6")

/* Options: int and long ones are Integer parameters with the table's range, double ones Real
 * (field: the option's name in the model's options struct). */
#define FMU_OPTION_FROM_TABLE(id, name, type, unit, min, min_closed, max, max_closed, start, \
                              description)                                                   \
    FMU_OPTION_FROM_TABLE_##type(id, name, unit, min, max, start, description)
#define FMU_OPTION_FROM_TABLE_int(id, name, unit, min, max, start, description) \
    FMU_OPTION_INT(id, name, #name, start, min, max, description)
#define FMU_OPTION_FROM_TABLE_long FMU_OPTION_FROM_TABLE_int
#define FMU_OPTION_FROM_TABLE_double(id, name, unit, min, max, start, description) \
    FMU_OPTION_REAL(id, name, #name, name, unit, description)

/* The plant's options (STEWART_PLANT_OPTION_TABLE): the same, with the Real ones bound to
 * options.<name> of the model's settings (plant_settings, fmu/models/plant/config.h). */
#define FMU_PLANT_OPTION_FROM_TABLE(id, name, type, unit, min, min_closed, max, max_closed, start, \
                                    description)                                                   \
    FMU_PLANT_OPTION_FROM_TABLE_##type(id, name, unit, min, max, start, description)
#define FMU_PLANT_OPTION_FROM_TABLE_int FMU_OPTION_FROM_TABLE_int
#define FMU_PLANT_OPTION_FROM_TABLE_long FMU_OPTION_FROM_TABLE_int
#define FMU_PLANT_OPTION_FROM_TABLE_double(id, name, unit, min, max, start, description) \
    FMU_OPTION_REAL(id, name, #name, options.name, unit, description)

#endif
