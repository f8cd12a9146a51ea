/* The XML species files Sylva writes (Arbaro's <arbaro>, grow presets' <grow-presets>): a root,
 * one <species name=…>, then <param name=… value=…/> lines and comments, indented by two,
 * attributes in single quotes. libxml2's xmlTextWriter does the escaping. */
#ifndef SYL_UTIL_PARAMXML_H
#define SYL_UTIL_PARAMXML_H
#include <stdio.h>

typedef struct ParamXml ParamXml;

/* A document open at <root><species name='species'>; NULL: out of memory. */
ParamXml *paramxml_begin(const char *root, const char *species);
void paramxml_param(ParamXml *x, const char *name, const char *value);
void paramxml_comment(ParamXml *x, const char *text);
/* An empty element <name a='v' …/>: attrs holds n name, value pairs (a NULL value: left out). */
void paramxml_element(ParamXml *x, const char *name, const char *const *attrs, int n);
/* Close the document, write it to out (NULL: nowhere, a caller's error) and free x: SYL_OK,
 * SYL_ELIMIT (out of memory in the writer, nothing written) or SYL_EIO. */
int paramxml_end(ParamXml *x, FILE *out);

#endif
