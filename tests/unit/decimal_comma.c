#define _POSIX_C_SOURCE 200809L
#include "decimal_comma.h"

#include <locale.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int use_decimal_comma(const char *dir) {
    if (!setlocale(LC_NUMERIC, "de_DE.UTF-8")) {
        char command[1024];
        mkdir(dir, 0755);
        /* -c: written despite the charmap's warnings, which make localedef exit 1 */
        snprintf(command, sizeof command, "localedef -c -i de_DE -f UTF-8 '%s/de_DE.UTF-8' 2>&1",
                 dir);
        if (system(command) == -1) return 0;
        setenv("LOCPATH", dir, 1);
        if (!setlocale(LC_NUMERIC, "de_DE.UTF-8")) return 0;
    }
    return strcmp(localeconv()->decimal_point, ",") == 0;
}

void use_decimal_point(void) { setlocale(LC_NUMERIC, "C"); }
