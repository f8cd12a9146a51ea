/* Fixture: a type of the lowest folder, with nothing to link. */
typedef struct LowPair { int a, b; } LowPair;
