/* libxml2, bound on first use (util/lazylib.h): include this instead of its headers. */
#ifndef SYL_UTIL_LAZY_XML_H
#define SYL_UTIL_LAZY_XML_H

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxml/xmlwriter.h>

#include "util/lazylib.h"

#define XML_FUNCS(X) \
    X(__xmlStructuredError) \
    X(__xmlStructuredErrorContext) \
    X(xmlBufferContent) \
    X(xmlBufferCreate) \
    X(xmlBufferFree) \
    X(xmlBufferLength) \
    X(xmlCtxtReadMemory) \
    X(xmlDocGetRootElement) \
    X(xmlFreeDoc) \
    X(xmlFreeParserCtxt) \
    X(xmlFreeTextWriter) \
    X(xmlGetLineNo) \
    X(xmlGetProp) \
    X(xmlNewParserCtxt) \
    X(xmlNewTextWriterMemory) \
    X(xmlNodeGetContent) \
    X(xmlSAX2GetLineNumber) \
    X(xmlSetStructuredErrorFunc) \
    X(xmlStopParser) \
    X(xmlTextWriterEndAttribute) \
    X(xmlTextWriterEndDocument) \
    X(xmlTextWriterEndElement) \
    X(xmlTextWriterSetIndent) \
    X(xmlTextWriterSetIndentString) \
    X(xmlTextWriterSetQuoteChar) \
    X(xmlTextWriterStartAttribute) \
    X(xmlTextWriterStartDocument) \
    X(xmlTextWriterStartElement) \
    X(xmlTextWriterWriteAttribute) \
    X(xmlTextWriterWriteComment) \
    X(xmlTextWriterWriteFormatAttribute) \
    X(xmlTextWriterWriteFormatString) \
    X(xmlTextWriterWriteString)

typedef struct XmlApi {
    XML_FUNCS(LAZY_LIB_FIELD)
} XmlApi;
const XmlApi *xml_api(void);

/* Each call goes through the table; a function missing here is an undefined symbol at link.
 * The error handler globals are calls of __xmlStructuredError() and its like; xmlFree is
 * a variable of the library (its thread-local allocators are off in Debian's build). */
#define __xmlStructuredError(...) xml_api()->__xmlStructuredError(__VA_ARGS__)
#define __xmlStructuredErrorContext(...) xml_api()->__xmlStructuredErrorContext(__VA_ARGS__)
#define xmlBufferContent(...) xml_api()->xmlBufferContent(__VA_ARGS__)
#define xmlBufferCreate(...) xml_api()->xmlBufferCreate(__VA_ARGS__)
#define xmlBufferFree(...) xml_api()->xmlBufferFree(__VA_ARGS__)
#define xmlBufferLength(...) xml_api()->xmlBufferLength(__VA_ARGS__)
#define xmlCtxtReadMemory(...) xml_api()->xmlCtxtReadMemory(__VA_ARGS__)
#define xmlDocGetRootElement(...) xml_api()->xmlDocGetRootElement(__VA_ARGS__)
#define xmlFreeDoc(...) xml_api()->xmlFreeDoc(__VA_ARGS__)
#define xmlFreeParserCtxt(...) xml_api()->xmlFreeParserCtxt(__VA_ARGS__)
#define xmlFreeTextWriter(...) xml_api()->xmlFreeTextWriter(__VA_ARGS__)
#define xmlGetLineNo(...) xml_api()->xmlGetLineNo(__VA_ARGS__)
#define xmlGetProp(...) xml_api()->xmlGetProp(__VA_ARGS__)
#define xmlNewParserCtxt(...) xml_api()->xmlNewParserCtxt(__VA_ARGS__)
#define xmlNewTextWriterMemory(...) xml_api()->xmlNewTextWriterMemory(__VA_ARGS__)
#define xmlNodeGetContent(...) xml_api()->xmlNodeGetContent(__VA_ARGS__)
#define xmlSAX2GetLineNumber(...) xml_api()->xmlSAX2GetLineNumber(__VA_ARGS__)
#define xmlSetStructuredErrorFunc(...) xml_api()->xmlSetStructuredErrorFunc(__VA_ARGS__)
#define xmlStopParser(...) xml_api()->xmlStopParser(__VA_ARGS__)
#define xmlTextWriterEndAttribute(...) xml_api()->xmlTextWriterEndAttribute(__VA_ARGS__)
#define xmlTextWriterEndDocument(...) xml_api()->xmlTextWriterEndDocument(__VA_ARGS__)
#define xmlTextWriterEndElement(...) xml_api()->xmlTextWriterEndElement(__VA_ARGS__)
#define xmlTextWriterSetIndent(...) xml_api()->xmlTextWriterSetIndent(__VA_ARGS__)
#define xmlTextWriterSetIndentString(...) xml_api()->xmlTextWriterSetIndentString(__VA_ARGS__)
#define xmlTextWriterSetQuoteChar(...) xml_api()->xmlTextWriterSetQuoteChar(__VA_ARGS__)
#define xmlTextWriterStartAttribute(...) xml_api()->xmlTextWriterStartAttribute(__VA_ARGS__)
#define xmlTextWriterStartDocument(...) xml_api()->xmlTextWriterStartDocument(__VA_ARGS__)
#define xmlTextWriterStartElement(...) xml_api()->xmlTextWriterStartElement(__VA_ARGS__)
#define xmlTextWriterWriteAttribute(...) xml_api()->xmlTextWriterWriteAttribute(__VA_ARGS__)
#define xmlTextWriterWriteComment(...) xml_api()->xmlTextWriterWriteComment(__VA_ARGS__)
#define xmlTextWriterWriteFormatAttribute(...) xml_api()->xmlTextWriterWriteFormatAttribute(__VA_ARGS__)
#define xmlTextWriterWriteFormatString(...) xml_api()->xmlTextWriterWriteFormatString(__VA_ARGS__)
#define xmlTextWriterWriteString(...) xml_api()->xmlTextWriterWriteString(__VA_ARGS__)
#undef xmlFree
#define xmlFree (*xml_free())
xmlFreeFunc *xml_free(void);

#endif
