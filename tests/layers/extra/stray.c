/* Fixture: a folder the rules do not place. */
int stray_value(void);
int stray_value(void) { return 3; }
