/* Fixture: the middle folder's function. */
int mid_value(void);
