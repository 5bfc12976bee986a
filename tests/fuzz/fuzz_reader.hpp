// The byte reader both fuzz targets draw their operations and values from.
#ifndef STEWART_FUZZ_READER_HPP
#define STEWART_FUZZ_READER_HPP

#include <cmath>
#include <cstdint>
#include <cstring>

namespace {

struct Reader {
    const uint8_t *p;
    size_t left;
    bool take(void *out, size_t n) {
        if (left < n) return false;
        std::memcpy(out, p, n);
        p += n;
        left -= n;
        return true;
    }
    uint8_t byte() {
        uint8_t b = 0;
        take(&b, 1);
        return b;
    }
    // A selector byte, then a value: specials, small decimals or a raw float64.
    double value() {
        static const double kSpecial[] = {
            0.0,      0.5,    -0.5,     1.0,       -1.0,  0.1,
            1e-9,     10.0,   M_PI / 2, -M_PI / 2, 1e-15, 1e3,
            1e300,    -1e300, HUGE_VAL, -HUGE_VAL, NAN,   2.2250738585072014e-308,
            4.9e-324, 1e-3,   100.0,    0.7,       0.4,   1e10,
            1e-300,   -0.0,   0.45,     0.55,      1e16,  1e308,
            3.0,      0.75};
        const uint8_t sel = byte();
        if (sel < 128) return kSpecial[sel % (sizeof kSpecial / sizeof kSpecial[0])];
        if (sel < 192) {
            int8_t small = 0;
            take(&small, 1);
            return small / 100.0;
        }
        double d = 0;
        take(&d, sizeof d);
        return d;
    }
};

}  // namespace

#endif
