// Loads an ontology file with the OWL API 3.4.3, as aRMOR does (not through Owlready2, whose own parser reads
// the file first), and prints Pellet 2.3.1's classes of every named individual as one JSON line:
// {"consistent": bool, "types": {individual IRI: [class IRI, ...]}}.
import com.clarkparsia.pellet.owlapiv3.PelletReasonerFactory;
import org.semanticweb.owlapi.apibinding.OWLManager;
import org.semanticweb.owlapi.model.*;
import org.semanticweb.owlapi.reasoner.OWLReasoner;

import java.io.File;
import java.util.TreeSet;

public class OwlApiTypes {
    public static void main(String[] args) throws Exception {
        OWLOntologyManager manager = OWLManager.createOWLOntologyManager();
        OWLOntology onto = manager.loadOntologyFromOntologyDocument(new File(args[0]));
        OWLReasoner reasoner = PelletReasonerFactory.getInstance().createNonBufferingReasoner(onto);
        if (!reasoner.isConsistent()) {
            System.out.println("{\"consistent\": false}");
            return;
        }
        StringBuilder out = new StringBuilder("{\"consistent\": true, \"types\": {");
        String sep = "";
        for (OWLNamedIndividual ind : onto.getIndividualsInSignature()) {
            TreeSet<String> types = new TreeSet<String>();
            for (OWLClass c : reasoner.getTypes(ind, false).getFlattened()) {
                if (!c.isOWLThing()) types.add("\"" + c.getIRI() + "\"");
            }
            out.append(sep).append("\"").append(ind.getIRI()).append("\": [").append(String.join(", ", types)).append("]");
            sep = ", ";
        }
        System.out.println(out.append("}}"));
    }
}
