# Floating-point operations are rounded as the source writes them: no fused multiply-add, which
# the compiler would otherwise form wherever the target processor has it (-march=native,
# x86-64-v3, aarch64). With it the same inputs would give other layers on another machine; Talus
# promises the same layers for the same seed. Builds for a newer x86-64 processor keep that
# promise with -march=... -mno-fma (docs/performance.md, "Building for a newer processor").
add_compile_options(-ffp-contract=off)
# Talus neither reads errno after a maths function nor traps floating-point exceptions, so it
# tells the compiler so: a square root is then one instruction, with no call for a negative
# argument, and a loop whose operations are all safe to run for every element may be vectorised
# (the pair loops of the mud flow). Neither option changes a rounded result.
add_compile_options(-fno-math-errno -fno-trapping-math)
