//! A small element tree over `quick-xml`, each element with the line it
//! starts on, so an error can name where in the file it is.

use quick_xml::events::{BytesStart, Event};

/// Deeper nesting than any tool's file has: refused, not followed.
const MAX_DEPTH: usize = 64;
/// The tree may take this many bytes for each byte of the file (and
/// [`MIN_BUDGET`] for a small one): past it the file is refused where it
/// stands, before the rest is built. A backstop: the formats' own counts
/// ([`Most`]) refuse a file asking for too much long before; an element
/// costs about 300 bytes and 110 an attribute, a real tool's file 5–11
/// times its size, many empty elements far more.
const BUDGET_PER_BYTE: usize = 16;
/// What one allocation costs beyond its bytes, about.
const ALLOCATION: usize = 32;
/// What any file may take, however small.
const MIN_BUDGET: usize = 4 << 20;

/// The most elements of one name a format reads, and why: counted as the
/// file is read, so a file asking for more is refused before they are built.
#[derive(Clone, Copy, Debug)]
pub struct Most {
    /// The element's name (case-insensitive).
    pub name: &'static str,
    /// How many the file may hold.
    pub count: usize,
    /// What a reader is told, after "more than N <name>: ".
    pub because: &'static str,
}

/// One element: its name, attributes, children and text, and its line.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Element {
    /// The tag's name.
    pub name: String,
    /// Attributes in file order, values unescaped.
    pub attributes: Vec<(String, String)>,
    /// Child elements in file order.
    pub children: Vec<Element>,
    /// The text directly inside it (unescaped, joined).
    pub text: String,
    /// The line (from 1) its start tag is on.
    pub line: usize,
}

/// The file is not well-formed XML.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("line {line}: {message}")]
pub struct XmlError {
    /// The line (from 1) the reader stopped on.
    pub line: usize,
    /// What is wrong.
    pub message: String,
    /// Well-formed as far as read, but asking for more than the format may
    /// hold ([`Most`], the tree's budget).
    pub too_much: bool,
}

impl Element {
    /// The value of attribute `name` (case-insensitive: tools differ).
    pub fn attr(&self, name: &str) -> Option<&str> {
        self.attributes.iter().find(|(key, _)| key.eq_ignore_ascii_case(name)).map(|(_, value)| value.as_str())
    }

    /// The first child named `name` (case-insensitive).
    pub fn child(&self, name: &str) -> Option<&Element> {
        self.children.iter().find(|child| child.name.eq_ignore_ascii_case(name))
    }

    /// The children named `name` (case-insensitive).
    pub fn children_named<'a>(&'a self, name: &'a str) -> impl Iterator<Item = &'a Element> + 'a {
        self.children.iter().filter(move |child| child.name.eq_ignore_ascii_case(name))
    }

    /// Every element below this one named `name`, in document order.
    pub fn descendants_named<'a>(&'a self, name: &str) -> Vec<&'a Element> {
        let mut found = Vec::new();
        let mut stack: Vec<&Element> = self.children.iter().rev().collect();
        while let Some(element) = stack.pop() {
            if element.name.eq_ignore_ascii_case(name) {
                found.push(element);
            }
            stack.extend(element.children.iter().rev());
        }
        found
    }
}

/// Lines of the text: where each begins.
struct Lines<'a> {
    text: &'a str,
    starts: Vec<usize>,
}

impl<'a> Lines<'a> {
    fn new(text: &'a str) -> Self {
        let starts = std::iter::once(0).chain(text.match_indices('\n').map(|(at, _)| at + 1)).collect();
        Self { text, starts }
    }

    /// The line (from 1) of byte `position`.
    fn at(&self, position: u64) -> usize {
        let position = usize::try_from(position).unwrap_or(usize::MAX).min(self.text.len());
        self.starts.partition_point(|&start| start <= position)
    }

    /// The line of the tag that ends just before `end`.
    fn of_tag_ending(&self, end: u64) -> usize {
        let end = usize::try_from(end).unwrap_or(usize::MAX).min(self.text.len());
        let start = self.text[..end].rfind('<').unwrap_or(0);
        self.at(u64::try_from(start).unwrap_or(u64::MAX))
    }
}

fn element(start: &BytesStart<'_>, line: usize) -> Result<Element, String> {
    let name = String::from_utf8_lossy(start.name().as_ref()).into_owned();
    let mut attributes = Vec::new();
    for attribute in start.attributes() {
        let attribute = attribute.map_err(|error| format!("<{name}>: {error}"))?;
        let key = String::from_utf8_lossy(attribute.key.as_ref()).into_owned();
        let value = attribute
            .normalized_value(quick_xml::XmlVersion::Implicit1_0)
            .map_err(|error| format!("<{name}> {key}: {error}"))?;
        attributes.push((key, value.into_owned()));
    }
    Ok(Element { name, attributes, children: Vec::new(), text: String::new(), line })
}

/// What the tree holds so far, against what the file may have it hold.
struct Tally<'m> {
    most: &'m [Most],
    counts: Vec<usize>,
    bytes: usize,
    budget: usize,
}

impl<'m> Tally<'m> {
    fn new(most: &'m [Most], text: &str) -> Self {
        let budget = text.len().saturating_mul(BUDGET_PER_BYTE).max(MIN_BUDGET);
        Self { most, counts: vec![0; most.len()], bytes: 0, budget }
    }

    /// One more element as read from its start tag: refused when its name
    /// passes its count, or the tree its budget.
    fn add(&mut self, start: &BytesStart<'_>) -> Result<(), String> {
        let name = start.name();
        let name = name.as_ref();
        if let Some(index) = self.most.iter().position(|most| most.name.as_bytes().eq_ignore_ascii_case(name)) {
            self.counts[index] += 1;
            let most = self.most[index];
            if self.counts[index] > most.count {
                return Err(format!("more than {} <{}>: {}", most.count, most.name, most.because));
            }
        }
        // Each attribute a pair of strings, each string an allocation of its own.
        let raw = start.attributes_raw();
        let attributes = raw.iter().filter(|byte| **byte == b'=').count();
        let pair = size_of::<(String, String)>() + 2 * ALLOCATION;
        // The element in its parent's list (which may hold as much again
        // spare), its name and its text.
        self.bytes += 2 * size_of::<Element>() + 2 * ALLOCATION + name.len() + raw.len() + attributes * pair;
        self.check()
    }

    /// Text put in the tree.
    fn text(&mut self, bytes: usize) -> Result<(), String> {
        self.bytes += bytes;
        self.check()
    }

    fn check(&self) -> Result<(), String> {
        if self.bytes > self.budget {
            return Err(format!(
                "the file's elements would take over {} MB, {BUDGET_PER_BYTE} times the file: is it damaged?",
                self.budget >> 20
            ));
        }
        Ok(())
    }
}

/// The character an entity or character reference stands for (`&amp;`, `&#233;`).
fn entity(reference: &quick_xml::events::BytesRef<'_>) -> Result<char, String> {
    if let Ok(Some(c)) = reference.resolve_char_ref() {
        return Ok(c);
    }
    let name = reference.decode().map_err(|error| error.to_string())?;
    match name.as_ref() {
        "amp" => Ok('&'),
        "lt" => Ok('<'),
        "gt" => Ok('>'),
        "quot" => Ok('"'),
        "apos" => Ok('\''),
        other => Err(format!("unknown entity &{other};")),
    }
}

/// The file's root element.
#[cfg(test)]
pub fn parse(text: &str) -> Result<Element, XmlError> {
    parse_within(text, &[])
}

/// The file's root element, the elements `most` names counted as they are
/// read: a file with more of one than its count, or whose tree would take
/// many times its size, is refused at the line where it passed, before the
/// rest is built.
pub fn parse_within(text: &str, most: &[Most]) -> Result<Element, XmlError> {
    let mut reader = quick_xml::Reader::from_str(text);
    let lines = Lines::new(text);
    let mut tally = Tally::new(most, text);
    let mut open: Vec<Element> = Vec::new();
    let mut root: Option<Element> = None;
    loop {
        let event = reader.read_event().map_err(|error| XmlError {
            line: lines.at(reader.error_position()),
            message: error.to_string(),
            too_much: false,
        })?;
        let before = lines.of_tag_ending(reader.buffer_position());
        let fail = |message: String| XmlError { line: before, message, too_much: false };
        let too_much = |message: String| XmlError { line: before, message, too_much: true };
        match event {
            Event::Start(start) => {
                if open.len() >= MAX_DEPTH {
                    return Err(fail(format!("elements nested over {MAX_DEPTH} deep")));
                }
                tally.add(&start).map_err(too_much)?;
                open.push(element(&start, before).map_err(fail)?);
            }
            Event::Empty(start) => {
                tally.add(&start).map_err(too_much)?;
                let done = element(&start, before).map_err(fail)?;
                match open.last_mut() {
                    Some(parent) => parent.children.push(done),
                    None if root.is_none() => root = Some(done),
                    None => return Err(fail(format!("<{}> after the root element", done.name))),
                }
            }
            Event::End(_) => {
                let mut done = open.pop().ok_or_else(|| fail("a closing tag with nothing open".into()))?;
                done.text = done.text.trim().to_string();
                match open.last_mut() {
                    Some(parent) => parent.children.push(done),
                    None => root = Some(done),
                }
            }
            Event::Text(text) => {
                if let Some(current) = open.last_mut() {
                    tally.text(text.len()).map_err(too_much)?;
                    current.text.push_str(&text.decode().map_err(|error| fail(error.to_string()))?);
                }
            }
            Event::CData(data) => {
                if let Some(current) = open.last_mut() {
                    tally.text(data.len()).map_err(too_much)?;
                    current.text.push_str(&data.decode().map_err(|error| fail(error.to_string()))?);
                }
            }
            Event::GeneralRef(reference) => {
                if let Some(current) = open.last_mut() {
                    current.text.push(entity(&reference).map_err(fail)?);
                }
            }
            Event::Eof => break,
            Event::Comment(_) | Event::Decl(_) | Event::PI(_) | Event::DocType(_) => {}
        }
    }
    if let Some(unclosed) = open.last() {
        return Err(XmlError {
            line: lines.at(u64::MAX),
            message: format!("<{}> (line {}) is never closed: is the file cut short?", unclosed.name, unclosed.line),
            too_much: false,
        });
    }
    root.ok_or(XmlError { line: 1, message: "no element at all: is it an XML file?".into(), too_much: false })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn elements_carry_their_lines_attributes_and_text() {
        let root = parse("<?xml version=\"1.0\"?>\n<A x=\"1 &amp; 2\">\n  <B/>\n  <c>t &lt; u</c>\n</A>\n").unwrap();
        assert_eq!((root.name.as_str(), root.line, root.attr("X")), ("A", 2, Some("1 & 2")));
        assert_eq!(root.children[0].line, 3);
        assert_eq!((root.child("C").unwrap().text.as_str(), root.child("c").unwrap().line), ("t < u", 4));
    }

    #[test]
    fn a_cut_file_and_garbage_say_where() {
        let cut = parse("<A>\n<B>\n").unwrap_err();
        assert!(cut.message.contains("<B> (line 2) is never closed"), "{cut}");
        let mismatched = parse("<A>\n\n</B>").unwrap_err();
        assert_eq!(mismatched.line, 3, "{mismatched}");
        assert!(parse("just words").is_err());
    }
}
