/* TEST-ONLY 32-bit arithmetic helpers that GCC calls for the dsPIC30F (its
   DIV instructions divide 32 bits by 16 only), for the bare programs of the
   simulator's tests. They stand in for the project's hal/dspic30 run-time
   helpers until those are on this branch, and are to be replaced by them.
   Results as GCC's libgcc documents them: quotients truncate toward zero, a
   remainder has the sign of the dividend. Shift and add or subtract only,
   so that nothing here calls a helper. */

typedef unsigned long u32;
typedef long s32;

u32 __udivsi3(u32 n, u32 d);
u32 __umodsi3(u32 n, u32 d);
s32 __divsi3(s32 n, s32 d);
s32 __modsi3(s32 n, s32 d);
s32 __mulsi3(s32 a, s32 b);

static u32 divide(u32 n, u32 d, u32 *rest)
{
    u32 q = 0, r = 0;
    int i;
    if (d == 0) {
        *rest = n;
        return 0xFFFFFFFFul;
    }
    for (i = 0; i < 32; i++) {
        r = (r << 1) | (n >> 31);
        n <<= 1;
        q <<= 1;
        if (r >= d) {
            r -= d;
            q |= 1;
        }
    }
    *rest = r;
    return q;
}

static u32 magnitude(s32 v)
{
    return v < 0 ? 0ul - (u32)v : (u32)v;
}

u32 __udivsi3(u32 n, u32 d)
{
    u32 r;
    return divide(n, d, &r);
}

u32 __umodsi3(u32 n, u32 d)
{
    u32 r;
    divide(n, d, &r);
    return r;
}

s32 __divsi3(s32 n, s32 d)
{
    u32 r;
    u32 q = divide(magnitude(n), magnitude(d), &r);
    return (s32)(((n < 0) != (d < 0)) ? 0ul - q : q);
}

s32 __modsi3(s32 n, s32 d)
{
    u32 r;
    divide(magnitude(n), magnitude(d), &r);
    return (s32)(n < 0 ? 0ul - r : r);
}

s32 __mulsi3(s32 a, s32 b)
{
    u32 x = (u32)a, y = (u32)b, p = 0;
    while (y != 0) {
        if (y & 1)
            p += x;
        x <<= 1;
        y >>= 1;
    }
    return (s32)p;
}
