# Checks an exercise sheet's Moodle quiz: quiz.xml parses as XML, has Moodle's question
# structure (a category, then numerical questions with a name, a question text, one answer
# of fraction 100 with a tolerance > 0), and every question's answer equals the value its
# <idnumber> ("NN/json/pointer") names in answers/NN.json. Prints "ok N" (N questions).
import json
import sys
import xml.etree.ElementTree as ET

folder = sys.argv[1]
root = ET.parse(folder + "/quiz.xml").getroot()
assert root.tag == "quiz", root.tag
questions = root.findall("question")
assert questions and questions[0].get("type") == "category", "no category first"
assert questions[0].find("category/text").text.startswith("$course$/")


def resolve(doc, pointer):
    for token in pointer.split("/")[1:]:
        token = token.replace("~1", "/").replace("~0", "~")
        doc = doc[int(token)] if isinstance(doc, list) else doc[token]
    return doc


count = 0
for q in questions[1:]:
    assert q.get("type") == "numerical", q.get("type")
    assert q.find("name/text").text.strip(), "a question without a name"
    assert q.find("questiontext").get("format") == "html"
    assert q.find("questiontext/text").text.strip(), "a question without text"
    answers = q.findall("answer")
    assert len(answers) == 1 and answers[0].get("fraction") == "100", "one answer of 100%"
    given = float(answers[0].find("text").text)
    tolerance = float(answers[0].find("tolerance").text)
    assert tolerance > 0, "tolerance"
    ident = q.find("idnumber").text
    nn, pointer = ident[:2], ident[2:]
    with open(folder + "/answers/" + nn + ".json") as f:
        want = float(resolve(json.load(f), pointer))
    assert abs(given - want) <= 1e-9 * max(1.0, abs(want)), (ident, given, want)
    assert tolerance < max(0.05 * abs(want), 0.01), (ident, tolerance)
    count += 1
print("ok", count)
