/* A decimal-comma numeric locale for the tests that numbers read the same in every locale: de_DE
 * from the system, or else built here by localedef into dir (Debian's `locales` package holds the
 * sources; scripts/setup.sh installs it). */
#ifndef STEWART_DECIMAL_COMMA_H
#define STEWART_DECIMAL_COMMA_H

#ifdef __cplusplus
extern "C" {
#endif

/* Sets LC_NUMERIC to de_DE.UTF-8, building it into dir if the system has none: 1 when the
 * process's decimal point is then ',', else 0 (the caller fails). */
int use_decimal_comma(const char *dir);
/* LC_NUMERIC back to "C". */
void use_decimal_point(void);

#ifdef __cplusplus
}
#endif

#endif
