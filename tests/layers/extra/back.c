/* Fixture: low reaching up to high, a forbidden edge that closes a cycle. */
int high_value(void);
int low_back(void);
int low_back(void) { return high_value(); }
