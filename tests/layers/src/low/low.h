/* Fixture: the lowest folder's function. */
int low_value(void);
