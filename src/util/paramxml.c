/* Species XML files (paramxml.h). */
#include "util/paramxml.h"

#include <stdlib.h>

#include "util/lazy_xml.h"

#include "sylva/sylva.h"

struct ParamXml {
    xmlBufferPtr buf;
    xmlTextWriterPtr tw;
    int rc; /* the first negative result of a writer call */
};

static void check(ParamXml *x, int rc) {
    if (rc < 0 && x->rc >= 0) x->rc = rc;
}

ParamXml *paramxml_begin(const char *root, const char *species) {
    ParamXml *x = calloc(1, sizeof *x);
    if (!x) return NULL;
    x->buf = xmlBufferCreate();
    x->tw = x->buf ? xmlNewTextWriterMemory(x->buf, 0) : NULL;
    if (!x->tw) {
        xmlBufferFree(x->buf);
        free(x);
        return NULL;
    }
    check(x, xmlTextWriterSetIndent(x->tw, 1));
    check(x, xmlTextWriterSetIndentString(x->tw, BAD_CAST "  "));
    check(x, xmlTextWriterSetQuoteChar(x->tw, '\''));
    check(x, xmlTextWriterStartDocument(x->tw, "1.0", NULL, NULL));
    check(x, xmlTextWriterStartElement(x->tw, BAD_CAST root));
    check(x, xmlTextWriterStartElement(x->tw, BAD_CAST "species"));
    check(x, xmlTextWriterWriteAttribute(x->tw, BAD_CAST "name", BAD_CAST species));
    return x;
}

void paramxml_param(ParamXml *x, const char *name, const char *value) {
    check(x, xmlTextWriterStartElement(x->tw, BAD_CAST "param"));
    check(x, xmlTextWriterWriteAttribute(x->tw, BAD_CAST "name", BAD_CAST name));
    check(x, xmlTextWriterWriteAttribute(x->tw, BAD_CAST "value", BAD_CAST value));
    check(x, xmlTextWriterEndElement(x->tw));
}

void paramxml_element(ParamXml *x, const char *name, const char *const *attrs, int n) {
    check(x, xmlTextWriterStartElement(x->tw, BAD_CAST name));
    for (int i = 0; i < n; i++)
        if (attrs[2 * i + 1]) check(x, xmlTextWriterWriteAttribute(x->tw, BAD_CAST attrs[2 * i], BAD_CAST attrs[2 * i + 1]));
    check(x, xmlTextWriterEndElement(x->tw));
}

void paramxml_comment(ParamXml *x, const char *text) { check(x, xmlTextWriterWriteComment(x->tw, BAD_CAST text)); }

int paramxml_end(ParamXml *x, FILE *out) {
    check(x, xmlTextWriterEndDocument(x->tw));
    xmlFreeTextWriter(x->tw); /* flushes into buf */
    int status = SYL_OK;
    if (x->rc < 0) status = SYL_ELIMIT;
    else if (out && fwrite(xmlBufferContent(x->buf), 1, (size_t)xmlBufferLength(x->buf), out) != (size_t)xmlBufferLength(x->buf))
        status = SYL_EIO;
    xmlBufferFree(x->buf);
    free(x);
    return status;
}
